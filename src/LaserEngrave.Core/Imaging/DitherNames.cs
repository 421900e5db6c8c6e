namespace LaserEngrave.Core.Imaging;

/// <summary>The dither methods' names as the command line and job files write them: none, floyd-steinberg, atkinson, bayer.</summary>
public static class DitherNames
{
    /// <summary>The names, for a message that lists them.</summary>
    public const string List = "none, floyd-steinberg, atkinson or bayer";

    /// <summary>The method a name means (case, '_' for '-', and a few aliases allowed); null for no name, <paramref name="unknown"/> true for a name that means none.</summary>
    public static DitherMethod Parse(string? text, out bool unknown)
    {
        unknown = false;
        switch (text?.Trim().ToLowerInvariant().Replace("_", "-", StringComparison.Ordinal))
        {
            case null or "" or "none":
                return DitherMethod.None;
            case "floyd-steinberg" or "floydsteinberg" or "fs":
                return DitherMethod.FloydSteinberg;
            case "atkinson":
                return DitherMethod.Atkinson;
            case "bayer" or "ordered":
                return DitherMethod.Bayer;
            default:
                unknown = true;
                return DitherMethod.None;
        }
    }

    /// <summary>The name <see cref="Parse"/> reads back.</summary>
    public static string Name(DitherMethod method) => method switch
    {
        DitherMethod.FloydSteinberg => "floyd-steinberg",
        DitherMethod.Atkinson => "atkinson",
        DitherMethod.Bayer => "bayer",
        _ => "none",
    };
}

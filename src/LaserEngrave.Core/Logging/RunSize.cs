using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Logging;

/// <summary>How the size was asked for, as a flat record the log can hold and a repeat can turn back into a <see cref="SizeSpec"/>.</summary>
/// <param name="By">Which value was given: width, height, widthAndHeight, pitch or resolution.</param>
/// <param name="WidthMm">The width asked for, mm (by width, widthAndHeight).</param>
/// <param name="HeightMm">The height asked for, mm (by height, widthAndHeight).</param>
/// <param name="PitchUm">The pitch asked for, µm (by pitch).</param>
/// <param name="Dpi">The image's resolution used, dots per inch (by resolution).</param>
public sealed record RunSize(RunSizeKind By, double? WidthMm = null, double? HeightMm = null, double? PitchUm = null, double? Dpi = null)
{
    /// <summary>The flat form of a size request.</summary>
    public static RunSize From(SizeSpec size) => size switch
    {
        SizeSpec.ByWidth w => new RunSize(RunSizeKind.Width, WidthMm: w.WidthMm),
        SizeSpec.ByHeight h => new RunSize(RunSizeKind.Height, HeightMm: h.HeightMm),
        SizeSpec.ByWidthAndHeight b => new RunSize(RunSizeKind.WidthAndHeight, WidthMm: b.WidthMm, HeightMm: b.HeightMm),
        SizeSpec.ByPitch p => new RunSize(RunSizeKind.Pitch, PitchUm: p.PitchUm),
        SizeSpec.ByResolution r => new RunSize(RunSizeKind.Resolution, Dpi: r.Dpi),
        _ => throw new ArgumentException($"size {size} has no log form", nameof(size)),
    };

    /// <summary>The size request again; throws <see cref="RunLogException"/> when the value its kind needs is missing.</summary>
    public SizeSpec ToSizeSpec() => By switch
    {
        RunSizeKind.Width => SizeSpec.Width(Need(WidthMm, "widthMm")),
        RunSizeKind.Height => SizeSpec.Height(Need(HeightMm, "heightMm")),
        RunSizeKind.WidthAndHeight => SizeSpec.WidthAndHeight(Need(WidthMm, "widthMm"), Need(HeightMm, "heightMm")),
        RunSizeKind.Pitch => SizeSpec.Pitch(Need(PitchUm, "pitchUm")),
        RunSizeKind.Resolution => SizeSpec.Resolution(Need(Dpi, "dpi")),
        _ => throw new RunLogException($"size kind {By} is not known"),
    };

    private double Need(double? value, string name) =>
        value ?? throw new RunLogException($"the size is by {By} but {name} is missing");
}

/// <summary>Which value a size request gave.</summary>
public enum RunSizeKind
{
    Width,
    Height,
    WidthAndHeight,
    Pitch,
    Resolution,
}

using System.Globalization;

namespace LaserEngrave.Core.Geometry;

/// <summary>How the user asks for the job's physical size: one of the nested cases.</summary>
/// <remarks>
/// Every case yields one square pixel pitch, because the edge formula places X and Y with the same pitch
/// (<see cref="JobGeometry"/>); see <see cref="ByWidthAndHeight"/> for what happens when both sides are given.
/// </remarks>
public abstract record SizeSpec
{
    private protected SizeSpec()
    {
    }

    /// <summary>Width in mm; the height follows from the image's aspect.</summary>
    public static SizeSpec Width(double widthMm) => new ByWidth(widthMm);

    /// <summary>Height in mm; the width follows from the image's aspect.</summary>
    public static SizeSpec Height(double heightMm) => new ByHeight(heightMm);

    /// <summary>Both sides in mm; they must agree with the image's aspect (see <see cref="ByWidthAndHeight"/>).</summary>
    public static SizeSpec WidthAndHeight(double widthMm, double heightMm) => new ByWidthAndHeight(widthMm, heightMm);

    /// <summary>The distance between pixel centres, µm.</summary>
    public static SizeSpec Pitch(double pitchUm) => new ByPitch(pitchUm);

    /// <summary>The image's own resolution (from its file), dots per inch.</summary>
    public static SizeSpec Resolution(double dpi) => new ByResolution(dpi);

    /// <summary>Short description for messages, e.g. "width 10 mm".</summary>
    public abstract string Describe();

    private protected static string Number(double value) => value.ToString("0.######", CultureInfo.InvariantCulture);

    /// <summary>Width in mm, aspect locked.</summary>
    public sealed record ByWidth(double WidthMm) : SizeSpec
    {
        public override string Describe() => $"width {Number(WidthMm)} mm";
    }

    /// <summary>Height in mm, aspect locked.</summary>
    public sealed record ByHeight(double HeightMm) : SizeSpec
    {
        public override string Describe() => $"height {Number(HeightMm)} mm";
    }

    /// <summary>Width and height in mm.</summary>
    /// <remarks>
    /// Separate X and Y pitches are not supported (the edge formula has one pitch), so both sides must match the
    /// image's aspect within <see cref="GeometryResolver.AspectTolerance"/>; the smaller of the two implied pitches is
    /// used, so the job stays inside the box, and the other side's shortfall shows in the residual scale error.
    /// A box of another aspect is refused with a message that gives the matching sizes.
    /// </remarks>
    public sealed record ByWidthAndHeight(double WidthMm, double HeightMm) : SizeSpec
    {
        public override string Describe() => $"{Number(WidthMm)} x {Number(HeightMm)} mm";
    }

    /// <summary>Pixel pitch in µm.</summary>
    public sealed record ByPitch(double PitchUm) : SizeSpec
    {
        public override string Describe() => $"pitch {Number(PitchUm)} µm";
    }

    /// <summary>The image's own resolution in dots per inch (one value: square pixels).</summary>
    public sealed record ByResolution(double Dpi) : SizeSpec
    {
        public override string Describe() => $"{Number(Dpi)} dpi";
    }
}

using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Simulator.Burn;

/// <summary>What a run actually burned, pulse by pulse, and what went wrong with the laser, as the burn recorder saw it.</summary>
/// <remarks>docs/simulator.md ("The burn recorder") defines every figure.</remarks>
public sealed record BurnReport
{
    /// <summary>The burned image on the job's grid: a pixel is set when at least one pulse landed on it.</summary>
    public required BitMask Burned { get; init; }

    /// <summary>Pulses landed per sub-cell, <see cref="DoseMap.SubcellsPerPixel"/> x <see cref="DoseMap.SubcellsPerPixel"/> per pixel.</summary>
    public required DoseMap Dose { get; init; }

    /// <summary>Pulses fired in all.</summary>
    public long Pulses { get; init; }

    /// <summary>Distance the stage moved, since the pulse before, for every laser-on-travel pulse, µm (both axes).</summary>
    public double LaserOnTravelUm { get; init; }

    /// <summary>Pulses that landed on a pixel the expected image has white, or off the grid.</summary>
    public int LaserOnTravelCount { get; init; }

    /// <summary>Laser-on stands (both axes still) longer than the dwell tolerance.</summary>
    public int DwellCount { get; init; }

    /// <summary>Total time of the counted dwells, s.</summary>
    public double DwellSeconds { get; init; }

    /// <summary>The longest laser-on stand, counted or not, s.</summary>
    public double LongestDwellSeconds { get; init; }

    /// <summary>Pulses fired below a tenth of the burn speed; null when the analysis was given no burn speed.</summary>
    public DwellFigures? Dwells { get; init; }

    /// <summary>Errors of the burn runs' first and last pulses; null without an expected image or a burn speed.</summary>
    public EdgeFigures? Edges { get; init; }

    /// <summary>Pulses per pixel over the expected image's black pixels (over the burned ones without an expected image).</summary>
    public required PulsesPerPixelFigures PulsesPerPixel { get; init; }

    /// <summary>Pulses fired while either axis was moving (velocity not zero); dot mode must have none.</summary>
    public long PulsesWhileMoving { get; init; }

    /// <summary>Move commands the stage answered with an error.</summary>
    public int RefusedMoves { get; init; }

    /// <summary>Total time the laser fired, s.</summary>
    public double LaserOnSeconds { get; init; }

    /// <summary>Number of burned pixels that the expected image has white (0 without an expected image).</summary>
    public long ExtraPixels { get; init; }

    /// <summary>Number of black pixels of the expected image that were not burned (0 without an expected image).</summary>
    public long MissingPixels { get; init; }

    /// <summary>Writes <see cref="Burned"/> as a PNG, black where burned, each pixel <paramref name="scale"/> x <paramref name="scale"/> image pixels.</summary>
    public void WritePng(string path, int scale = 1) => PngWriter.WriteMask(path, Burned, scale);

    /// <inheritdoc cref="WritePng(string, int)"/>
    public void WritePng(Stream output) => PngWriter.WriteMask(output, Burned);

    /// <summary>Writes <see cref="Dose"/> as an 8-bit grey PNG at 4 x 4 sub-cells a pixel: white = no pulse, black = the most.</summary>
    public void WriteDosePng(string path) => Dose.WritePng(path);

    /// <inheritdoc cref="WriteDosePng(string)"/>
    public void WriteDosePng(Stream output) => Dose.WritePng(output);
}

using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Simulator.Burn;

/// <summary>What a run actually burned, and what went wrong with the laser, as the burn recorder saw it.</summary>
public sealed record BurnReport
{
    /// <summary>The burned image on the job's grid: a pixel is set when the laser was on over at least half its width along its row's centre line.</summary>
    public required BitMask Burned { get; init; }

    /// <summary>Distance travelled with the laser on where it should have been off (over white, off the grid, or while Y moved), µm.</summary>
    public double LaserOnTravelUm { get; init; }

    /// <summary>Number of separate stretches of laser-on travel.</summary>
    public int LaserOnTravelCount { get; init; }

    /// <summary>Laser-on stands (both axes still) longer than the dwell tolerance.</summary>
    public int DwellCount { get; init; }

    /// <summary>Total time of the counted dwells, s.</summary>
    public double DwellSeconds { get; init; }

    /// <summary>The longest laser-on stand, counted or not, s.</summary>
    public double LongestDwellSeconds { get; init; }

    /// <summary>Move commands the stage answered with an error.</summary>
    public int RefusedMoves { get; init; }

    /// <summary>Total time the laser fired, s.</summary>
    public double LaserOnSeconds { get; init; }

    /// <summary>Number of burned pixels that the expected image has white (0 without an expected image).</summary>
    public long ExtraPixels { get; init; }

    /// <summary>Number of black pixels of the expected image that were not burned (0 without an expected image).</summary>
    public long MissingPixels { get; init; }

    /// <summary>Writes <see cref="Burned"/> as a PNG, black where burned.</summary>
    public void WritePng(string path) => PngWriter.WriteMask(path, Burned);

    /// <inheritdoc cref="WritePng(string)"/>
    public void WritePng(Stream output) => PngWriter.WriteMask(output, Burned);
}

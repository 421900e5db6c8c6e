using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Marks;

/// <summary>
/// A mark as asked for: a code (QR or Data Matrix) with its text beneath, or a text alone; in copies on a grid, each with
/// its own number. Values left null take the defaults or the machine profile's (process). docs/marking.md lists them.
/// </summary>
public sealed record MarkSpec
{
    /// <summary>The most copies one array may have: each is a layer or two of one job.</summary>
    public const int MaxCopies = 400;

    /// <summary>The text, with placeholders (<see cref="MarkText.Placeholders"/>).</summary>
    public required string Text { get; init; }

    /// <summary>The code, or null for a text alone.</summary>
    public CodeKind? Code { get; init; }

    /// <summary>A module's side, µm; or give <see cref="SizeMm"/>.</summary>
    public double? ModuleUm { get; init; }

    /// <summary>The code's side without its quiet zone, mm; or give <see cref="ModuleUm"/>.</summary>
    public double? SizeMm { get; init; }

    /// <summary>White modules around the code; null: 4 for QR, 1 for Data Matrix (their standards' quiet zones).</summary>
    public int? QuietModules { get; init; }

    /// <summary>QR error correction L, M, Q or H (M when null); none for a Data Matrix.</summary>
    public char? ErrorCorrection { get; init; }

    /// <summary>Whether a code has its text written beneath it (a text alone is always written).</summary>
    public bool Label { get; init; } = true;

    /// <summary>Capital height of the text, mm.</summary>
    public double TextHeightMm { get; init; } = 0.4;

    public TextAlign Align { get; init; } = TextAlign.Center;

    /// <summary>Baseline to baseline, in text heights.</summary>
    public double LineSpacing { get; init; } = 1.6;

    /// <summary>A system font's family, filled as raster; null: the engraving font's strokes.</summary>
    public string? Font { get; init; }

    /// <summary>Between the code's quiet zone and the text, mm.</summary>
    public double GapMm { get; init; } = 0.1;

    /// <summary>The first copy's top-left corner (of the code's quiet zone, or of the text), mm.</summary>
    public OriginMm Origin { get; init; } = new(10, 10);

    public int Copies { get; init; } = 1;

    /// <summary>Copies in a row of the grid (more than the copies: all in one row); null: all in one row, up to ten.</summary>
    public int? Columns { get; init; }

    /// <summary>From one copy to the next along X and Y, mm; null: the copy's size plus 1 mm.</summary>
    public double? PitchXMm { get; init; }

    /// <inheritdoc cref="PitchXMm"/>
    public double? PitchYMm { get; init; }

    public double? SpeedMmPerS { get; init; }

    public double? FrequencyHz { get; init; }

    public int Passes { get; init; } = 1;

    /// <summary>The quiet zone in force.</summary>
    public int Quiet => QuietModules ?? (Code == CodeKind.Qr ? 4 : 1);
}

using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Jobs;

/// <summary>One layer of a job: what it burns (an image, or a drawing or one of its layers), where, how, and how often.</summary>
/// <remarks>Values left null take the machine profile's (process) or the defaults (drawing options); docs/vectors.md, "Layers".</remarks>
public sealed record JobLayer
{
    /// <summary>The layer's name, for the log and the progress.</summary>
    public required string Name { get; init; }

    /// <summary>The image or drawing file.</summary>
    public required string Source { get; init; }

    public LayerMode Mode { get; init; } = LayerMode.Outline;

    /// <summary>For a drawing: only the paths on this layer of it (placed where they are in the whole drawing).</summary>
    public string? DrawingLayer { get; init; }

    /// <summary>Width on the stage, mm: required for an image; for a drawing null keeps its own units.</summary>
    public double? WidthMm { get; init; }

    public OriginMm Origin { get; init; } = OriginMm.Zero;

    public double? SpeedMmPerS { get; init; }

    public double? FrequencyHz { get; init; }

    public int Passes { get; init; } = 1;

    /// <summary>For an image: how it becomes a burn mask (threshold, dither, invert); the defaults when not given.</summary>
    public Imaging.MaskOptions Mask { get; init; } = Imaging.MaskOptions.Default;

    /// <summary>How a drawing layer's shapes are burned (outline, fill or both); an image layer's is outline, unused.</summary>
    public Vectors.VectorFillMode Fill => Mode switch
    {
        LayerMode.Fill => Vectors.VectorFillMode.Fill,
        LayerMode.Both => Vectors.VectorFillMode.Both,
        _ => Vectors.VectorFillMode.Outline,
    };

    /// <summary>For a drawing: the chord tolerance, µm (default 1).</summary>
    public double? ToleranceUm { get; init; }

    /// <summary>For a drawing's fill: the scan lines' pitch, µm (default 20).</summary>
    public double? FillPitchUm { get; init; }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Jobs;

/// <summary>Everything that defines an engraving job before the machine moves: image, mask, size, plan and process.</summary>
public sealed record JobSpec
{
    /// <summary>The most passes a job may have.</summary>
    public const int MaxPasses = 100;

    public required string ImagePath { get; init; }

    public MaskOptions Mask { get; init; } = MaskOptions.Default;

    public required SizeSpec Size { get; init; }

    public OriginMm Origin { get; init; } = OriginMm.Zero;

    public PlanOptions Plan { get; init; } = new();

    public ProcessSettings Process { get; init; } = ProcessSettings.Default;

    public MachineProfile Profile { get; init; } = MachineProfile.Default;

    /// <summary>How many times the plan is burned over the same place, one pass after the other; 1..<see cref="MaxPasses"/>.</summary>
    public int Passes { get; init; } = 1;
}

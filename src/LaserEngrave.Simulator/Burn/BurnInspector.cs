using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Simulator.Burn;

/// <summary>The simulator's burn check for a run (the host's EngraveSession asks it through <see cref="IRunInspector"/>): what its recorder saw, against the job's mask, for the log.</summary>
/// <remarks>Only what happened since <see cref="Begin"/> counts, so a run on a simulator that has burned before (the app's) is checked alone.</remarks>
public sealed class BurnInspector(SimulatedMachine machine) : ITwinInspector
{
    public PathReport? PathReport { get; private set; }

    public BurnReport? Report { get; private set; }

    public double NowSeconds => machine.NowSeconds;

    /// <summary>The twin itself, for what looks at it besides the burn check (the twin's camera).</summary>
    public SimulatedMachine Machine => machine;

    public BurnReport AnalyzeSince(BurnGrid grid, double startSeconds)
    {
        // Every job's check started its own window; this one starts where the caller says.
        machine.Recorder.Restart(startSeconds);
        return machine.Recorder.Analyze(grid);
    }

    public void Begin() => machine.Recorder.Restart(machine.NowSeconds);

    public RunSimulation Inspect(PreparedJob job, RunStopPoint? resumedFrom = null)
    {
        ArgumentNullException.ThrowIfNull(job);
        var expected = resumedFrom is null ? job.Mask : ResumedBurn.StillToBurn(job, resumedFrom);
        // In dot mode nothing burns in motion: no edges or dwells to measure against a burn speed, only the pulses while moving (none).
        var dots = job.Dots is not null;
        var burn = machine.Recorder.Analyze(BurnGrid.For(job.Plan.Geometry), expected, dots ? null : job.Spec.Process.BurnSpeedMmPerS);
        Report = burn;
        var simulation = new RunSimulation(
            machine.Options.Seed,
            burn.Pulses,
            burn.Edges is { } e ? new EdgeErrors(e.Count, e.MeanErrorUm, e.MaxErrorUm) : null,
            burn.Dwells is { } d ? new DwellCounts(d.Count, d.Pulses) : null,
            new PulseCountRange(burn.PulsesPerPixel.Min, burn.PulsesPerPixel.Mean, burn.PulsesPerPixel.Max),
            burn.LaserOnTravelCount,
            burn.MissingPixels,
            burn.ExtraPixels,
            burn.PulsesWhileMoving);
        return simulation with { Focus = Focus() };
    }

    /// <summary>Where Z stood while the laser fired and the spot the twin's beam gives there; null without a Z axis.</summary>
    public FocusFigures? Focus()
    {
        if (machine.Profile.Z is not { } z || machine.Recorder.FocusWhileFiring() is not { } firing)
        {
            return null;
        }

        var zUm = StageUnits.MicrostepsToUm((firing.MinMicrosteps + firing.MaxMicrosteps) / 2, z.MicrostepUm);
        var defocusUm = zUm - (Units.MmToUm(z.FocusMm) + machine.Options.TrueFocusOffsetUm);
        double? spot = machine.Options.RayleighLengthUm is { } zR
            ? machine.Profile.SpotDiameterUm * Math.Sqrt(1 + Math.Pow(defocusUm / zR, 2))
            : null;
        return new FocusFigures((long)Math.Round(firing.MinMicrosteps), (long)Math.Round(firing.MaxMicrosteps), firing.PeriodsWhileMoving, defocusUm, spot);
    }

    public RunSimulation InspectDrawing(PreparedDrawing drawing)
    {
        ArgumentNullException.ThrowIfNull(drawing);
        var burn = machine.Recorder.AnalyzePaths(drawing.Plan.Paths, drawing.Spec.Process.BurnSpeedMmPerS);
        PathReport = burn;
        return new RunSimulation(
            machine.Options.Seed,
            burn.Pulses,
            null,
            new DwellCounts(burn.DwellCount, burn.DwellPulses),
            new PulseCountRange(0, 0, 0),
            burn.OffPathPulses,
            0,
            0)
        {
            Path = new PathFigures(
                new MeanMax(burn.DeviationMeanUm, burn.DeviationMaxUm),
                new SpacingRange(burn.SpacingMinUm, burn.SpacingMeanUm, burn.SpacingMaxUm),
                burn.ExpectedSpacingUm,
                burn.OffPathPulses),
        };
    }
}

using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Sweeps;
using LaserEngrave.Core.Tests.Logging;

namespace LaserEngrave.Core.Tests.Jobs;

/// <summary>
/// The job rules answer the same on every path: a value the app's fields, the command line, a preset, a job file, a sweep
/// or a run log once accepted while another refused it now gets one answer (issue 23, item 3).
/// </summary>
public sealed class JobRulesTests : IDisposable
{
    /// <summary>A stage whose Y axis is slower and gentler than X, on a gate that takes at most 500 Hz.</summary>
    private static readonly MachineProfile SlowY = new()
    {
        Y = new AxisProfile { DeviceNumber = 2, MaxSpeedMmPerS = 2, MaxAccelerationMmPerS2 = 100 },
        Gate = new LaserGateProfile { MaxFrequencyHz = 500 },
        LaserFrequencyHz = 400,
        TravelSpeedMmPerS = 2,
    };

    private readonly TestRuns runs = new();

    private static MachineLimits Limits => MachineLimits.Of(SlowY);

    /// <summary>The job the profile suggests, every value within it.</summary>
    private static JobSettings Basis => JobSettings.From(ProcessSettings.FromProfile(SlowY));

    [Fact]
    public void Check_DefaultSettingsOnTheDefaultMachine_NoProblem()
    {
        Assert.Empty(JobRules.Check(new JobSettings(), MachineLimits.Of(MachineProfile.Default)));
        Assert.Empty(MachineProfileValidator.Problems(SlowY));
        Assert.Empty(JobRules.Check(Basis, Limits));
    }

    [Fact]
    public void Check_BurnSpeedAboveTheSlowerAxis_RefusedByEveryPath()
    {
        // The app once held the burn speed to X's 4 mm/s alone; the command line to min(X, Y).
        var problem = Assert.Single(JobRules.Check(Basis with { BurnSpeedMmPerS = 3 }, Limits));
        Assert.Equal(JobField.BurnSpeed, problem.Field);
        Assert.Equal("burn speed 3 mm/s: outside what the stage takes, 0.00093..2 mm/s (the profile's maxSpeedMmPerS)", problem.Message);

        Assert.Equal("process.burnSpeedMmPerS 3: outside what the stage takes, 0.00093..2 mm/s (the profile's maxSpeedMmPerS)", LogProblem(r => r with { Process = r.Process with { BurnSpeedMmPerS = 3 } }));
        Assert.Contains(new ProcessPreset { Name = "fast", BurnSpeedMmPerS = 3 }.Check(Limits), p => p.Field == JobField.BurnSpeed);
        Assert.Contains("speedMmPerS 3: outside what the stage takes", LayerProblem(new JobLayer { Name = "l", Source = runs.ImagePath, Mode = LayerMode.Raster, WidthMm = 5, SpeedMmPerS = 3 }), StringComparison.Ordinal);
        Assert.Contains("speed 3 mm/s: outside what the stage takes", SweepProblem("speed=1,3"), StringComparison.Ordinal);
    }

    [Fact]
    public void Check_FrequencyAboveTheProfilesGate_RefusedByEveryPath()
    {
        // The app once held the frequency to a fixed 100 kHz; the command line to the profile's gate.maxFrequencyHz.
        Assert.Equal(JobField.Frequency, Assert.Single(JobRules.Check(Basis with { LaserFrequencyHz = 1000 }, Limits)).Field);
        Assert.StartsWith("process.laserFrequencyHz 1000: outside what the laser gate takes, 1..500 Hz", LogProblem(r => r with { Process = r.Process with { LaserFrequencyHz = 1000 } }), StringComparison.Ordinal);
        Assert.Contains(new ProcessPreset { Name = "hot", LaserFrequencyHz = 1000 }.Check(Limits), p => p.Field == JobField.Frequency);
        Assert.Contains("frequencyHz 1000: outside what the laser gate takes", LayerProblem(new JobLayer { Name = "l", Source = runs.ImagePath, Mode = LayerMode.Raster, WidthMm = 5, FrequencyHz = 1000 }), StringComparison.Ordinal);
        Assert.Contains("frequency 1000 Hz: outside what the laser gate takes", SweepProblem("frequency=100,1000"), StringComparison.Ordinal);
    }

    [Fact]
    public void Check_AccelerationBelowOneUnitOrAboveTheSlowerAxis_RefusedByEveryPath()
    {
        // The app once took any acceleration above 0 up to X's maximum.
        foreach (var acceleration in new[] { 0.5, 150 })
        {
            Assert.Equal(JobField.Acceleration, Assert.Single(JobRules.Check(Basis with { AccelerationMmPerS2 = acceleration }, Limits)).Field);
            Assert.StartsWith($"process.accelerationMmPerS2 {acceleration}: outside what the stage takes", LogProblem(r => r with { Process = r.Process with { AccelerationMmPerS2 = acceleration } }), StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Check_OverscanPastTheTravel_RefusedByEveryPath()
    {
        // The app and the presets once took any overscan of 0 or more; the command line and the logs at most the X travel.
        Assert.Equal(JobField.Overscan, Assert.Single(JobRules.Check(Basis with { OverscanMm = 100 }, Limits)).Field);
        Assert.StartsWith("plan.overscanMm 100: must be 0..60 mm", LogProblem(r => r with { Plan = r.Plan with { OverscanMm = 100 } }), StringComparison.Ordinal);
        Assert.Contains(new ProcessPreset { Name = "wide", OverscanMm = 100 }.Check(Limits), p => p.Field == JobField.Overscan);
    }

    [Fact]
    public void Check_PitchOfFiveMillimetres_AcceptedByEveryPath()
    {
        // The app once refused a pitch above 1000 µm that the command line, the logs and the presets took.
        Assert.Empty(JobRules.Check(Basis with { SizeMode = SizeMode.Pitch, PitchUm = 5000 }, Limits));
        Assert.Null(LogProblem(r => r with { Geometry = r.Geometry with { Size = new RunSize(RunSizeKind.Pitch, PitchUm: 5000) } }));
        Assert.Empty(new ProcessPreset { Name = "coarse", PitchUm = 5000, LaserFrequencyHz = 400, TravelSpeedMmPerS = 2 }.Check(Limits));
    }

    [Fact]
    public void Check_PitchBelowAMicrostep_RefusedByEveryPath()
    {
        // The app and the presets once took any pitch above 0; the command line and the sweeps refused one below a microstep.
        Assert.Contains("below one microstep", Assert.Single(JobRules.Check(Basis with { SizeMode = SizeMode.Pitch, PitchUm = 0.05 }, Limits)).Message, StringComparison.Ordinal);
        Assert.StartsWith("geometry.size.pitchUm 0.05: below one microstep", LogProblem(r => r with { Geometry = r.Geometry with { Size = new RunSize(RunSizeKind.Pitch, PitchUm: 0.05) } }), StringComparison.Ordinal);
        Assert.Contains(new ProcessPreset { Name = "fine", PitchUm = 0.05, LaserFrequencyHz = 400 }.Check(Limits), p => p.Field == JobField.Pitch);
        Assert.Contains("pitch 0.05 µm: below one microstep", SweepProblem("pitch=20,0.05"), StringComparison.Ordinal);
    }

    [Fact]
    public void Check_DotPitchZero_OneDotAPixelOnEveryPath()
    {
        // The command line once refused --dot-pitch-microsteps 0, which the app and the logs took as one dot a pixel.
        Assert.Empty(JobRules.Check(Basis with { Mode = PlanMode.Dots, DotPitchMicrosteps = 0 }, Limits));
        Assert.Equal(JobField.DotPitch, Assert.Single(JobRules.Check(Basis with { Mode = PlanMode.Dots, DotPitchMicrosteps = -1 }, Limits)).Field);
    }

    [Fact]
    public void Check_Seed001PresetAtItsPitch_RefusedAsTheEngineRefusesIt()
    {
        // Seed 001's preset (20 kHz, 2 mm/s, 20 µm) makes 10 ms pixels, shorter than the gate needs: the engine refuses
        // such a job at preflight, so the rules refuse it beside the burn speed before anything starts.
        var preset = ProcessPreset.Examples[1];
        Assert.Empty(preset.Check(MachineLimits.Of(MachineProfile.Default)));
        var job = PreparedJob.Prepare(runs.Spec() with
        {
            Size = SizeSpec.Pitch(preset.PitchUm),
            Process = ProcessSettings.Default with { LaserFrequencyHz = preset.LaserFrequencyHz, BurnSpeedMmPerS = preset.BurnSpeedMmPerS, TravelSpeedMmPerS = preset.TravelSpeedMmPerS },
        });

        var problem = JobRules.Check(job);

        Assert.NotNull(job.EngraveProblem);
        Assert.NotNull(problem);
        Assert.Equal(JobField.BurnSpeed, problem.Field);
        Assert.Contains("shorter than the", problem.Message, StringComparison.Ordinal);
        Assert.Null(JobRules.Check(PreparedJob.Prepare(runs.Spec())));
    }

    [Fact]
    public void Check_FivePulsesASecondOnTheQrAtFiveMillimetres_RefusedBeforeAnythingMoves()
    {
        // Issue 31, finding 5: at 5 Hz and 1 mm/s a 122 µm pixel gets 0.61 pulses; the run "completed" with 173 pixels missing.
        var job = PreparedJob.Prepare(runs.Spec() with { Process = ProcessSettings.Default with { BurnSpeedMmPerS = 1, LaserFrequencyHz = 5 } });

        var problem = JobRules.Check(job);

        Assert.NotNull(problem);
        Assert.Equal(JobField.Frequency, problem.Field);
        Assert.Equal("laser frequency 5 Hz: gives each 121.95 µm pixel only 0.61 pulses at the burn speed of 1 mm/s, so some pixels would get none: give at least 9 Hz, or a burn speed of at most 0.609 mm/s", problem.Message);
        Assert.Equal(problem.Message.Replace("Hz:", "Hz", StringComparison.Ordinal), job.EngraveProblem);
    }

    [Fact]
    public void Check_FrequencyGivingAPulseEveryPixel_Accepted()
    {
        // The frequency the refusal names is one the rule takes.
        var job = PreparedJob.Prepare(runs.Spec() with { Process = ProcessSettings.Default with { BurnSpeedMmPerS = 1, LaserFrequencyHz = 9 } });

        Assert.Null(JobRules.Check(job));
        Assert.Null(job.EngraveProblem);
    }

    [Fact]
    public void Check_FractionOfAHertz_RefusedByEveryPath()
    {
        // Issue 31, finding 5: 0.5 Hz was logged as 0.5 while the gate was sent 1 Hz; a fraction is refused, not rounded.
        var problem = Assert.Single(JobRules.Check(Basis with { LaserFrequencyHz = 0.5 }, Limits));
        Assert.Equal(JobField.Frequency, problem.Field);
        Assert.Equal("laser frequency 0.5 Hz: is not a whole number of Hz: the laser gate is sent whole Hz; give 1", problem.Message);
        Assert.Contains(JobRules.Check(Basis with { LaserFrequencyHz = 400.4 }, Limits), p => p.Field == JobField.Frequency);
        Assert.StartsWith("process.laserFrequencyHz 0.5: is not a whole number of Hz", LogProblem(r => r with { Process = r.Process with { LaserFrequencyHz = 0.5 } }), StringComparison.Ordinal);
        Assert.Contains("is not a whole number of Hz", SweepProblem("frequency=100,100.5"), StringComparison.Ordinal);
    }

    public void Dispose() => runs.Dispose();

    private string? LogProblem(Func<RunRecord, RunRecord> change) => RunReplay.Problem(change(runs.FailedRecord() with { Profile = SlowY, Process = ProcessSettings.FromProfile(SlowY), StoppedAt = null }));

    private static string LayerProblem(JobLayer layer) => Assert.Throws<PlanException>(() => LayeredJob.Prepare([layer], SlowY)).Message;

    private static string SweepProblem(string rows) => Assert.Throws<SweepException>(() => SweepPlan.Build(new SweepSpec
    {
        Rows = SweepAxis.Parse(rows, "--rows"),
        Process = ProcessSettings.FromProfile(SlowY),
        Profile = SlowY,
    })).Message;
}

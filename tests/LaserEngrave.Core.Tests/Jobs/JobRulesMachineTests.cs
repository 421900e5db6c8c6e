using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Tests.Vectors;
using LaserEngrave.Core.Vectors;

namespace LaserEngrave.Core.Tests.Jobs;

/// <summary>
/// The rules beyond a job's fields (issue 35): a test fire, a jog step, where a job may stand, the process values alone
/// and equal microsteps, each answered once, in one sentence, for the command line, the app, the API and the devices.
/// </summary>
public sealed class JobRulesMachineTests
{
    private static string Qr => Path.Combine(Path.GetDirectoryName(TestDrawings.Folder)!, "qr-code.bmp");

    [Theory]
    [InlineData(1, true)]
    [InlineData(100_001, true)]
    [InlineData(1_000_000, true)]
    [InlineData(0, false)]
    [InlineData(1_000_001, false)]
    public void TestFirePulses_TheGatesBurstRange_OneRangeForEveryFrontEnd(long pulses, bool allowed)
    {
        // The app once held a test fire to 100,000 pulses, the command line to 1,000,000, the devices to none.
        var rule = JobRules.TestFirePulses(pulses);

        Assert.Equal(allowed, rule is null);
        if (!allowed)
        {
            Assert.Equal("must be 1..1000000 pulses (the laser gate's burst range)", rule);
        }
    }

    [Theory]
    [InlineData(60_000, 60, null)]
    [InlineData(-60_000, 60, null)]
    [InlineData(100_000, 150, null)]
    [InlineData(60_001, 60, "longer than the X travel (60000 µm)")]
    [InlineData(0, 60, "must be a finite number other than 0")]
    [InlineData(double.NaN, 60, "must be a finite number other than 0")]
    public void JogStep_AgainstTheAxisTravel_NotAFixedNumber(double stepUm, double travelMm, string? expected)
    {
        // The app once held a jog step to a fixed 60,000 µm whatever the stage; the command line to the travel.
        Assert.Equal(expected, JobRules.JogStep(stepUm, travelMm, "X"));
    }

    [Theory]
    [InlineData(null, true)]
    [InlineData(0.5, true)]
    [InlineData(0.0, false)]
    [InlineData(-5.0, false)]
    [InlineData(double.PositiveInfinity, false)]
    public void PulseEnergy_ZeroOrBelow_RefusedNotIgnored(double? energy, bool allowed)
    {
        Assert.Equal(allowed, JobRules.PulseEnergy(energy) is null);
        Assert.Equal(allowed, JobRules.Check(new JobSettings { PulseEnergyUj = energy }, MachineLimits.Of(MachineProfile.Default)).All(p => p.Field != JobField.PulseEnergy));
        Assert.Equal(allowed, JobRules.Check(ProcessSettings.Default with { PulseEnergyUj = energy }, MachineLimits.Of(MachineProfile.Default)).Count == 0);
    }

    [Fact]
    public void Placement_ImageOffTheTravel_OneSentenceForTheStartTheCliAndTheApp()
    {
        var inside = PreparedJob.Prepare(new JobSpec { ImagePath = Qr, Size = SizeSpec.Width(4), Origin = new OriginMm(56, 2) });
        var outside = PreparedJob.Prepare(new JobSpec { ImagePath = Qr, Size = SizeSpec.Width(4), Origin = new OriginMm(57, 2) });

        Assert.Null(JobRules.Placement(inside));
        Assert.Equal("the job (4 x 4 mm at origin 57, 2 mm) does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", JobRules.Placement(outside));
        Assert.Equal(JobRules.Placement(outside), EngraveJob.Of(outside).StartProblem);
    }

    [Fact]
    public void Placement_DrawingWhoseRunUpsLeaveTheTravel_RefusedThoughItsPathsFit()
    {
        // A drawing's strokes start before and end after its paths: the rule counts them, as the engine does.
        var spec = new JobSpec { ImagePath = TestDrawings.File("hexagons.dxf"), Size = SizeSpec.Width(10), Origin = new OriginMm(50, 4) };
        var drawing = PreparedDrawing.Prepare(spec, new VectorOptions());

        Assert.True(drawing.Plan.FitsTravel);
        Assert.False(drawing.FitsTravel);
        Assert.StartsWith("the drawing (10 x ", JobRules.Placement(drawing), StringComparison.Ordinal);
        Assert.EndsWith("mm at origin 50, 4 mm, with its strokes' run-ups and run-outs) does not fit the stage's travel (60 x 60 mm): move the origin or make it smaller", JobRules.Placement(drawing), StringComparison.Ordinal);
    }

    [Fact]
    public void Require_ProcessOutsideTheMachine_RefusedWhereTheWeakerCheckTookIt()
    {
        // ProcessSettings.Validate took any speed above 0; a job prepared in code now meets the fields' rules.
        var spec = new JobSpec { ImagePath = Qr, Size = SizeSpec.Width(4), Process = ProcessSettings.Default with { BurnSpeedMmPerS = 100 } };

        var ex = Assert.Throws<PlanException>(() => PreparedJob.Prepare(spec));

        Assert.Equal("burn speed 100 mm/s: outside what the stage takes, 0.00093..4 mm/s (the profile's maxSpeedMmPerS)", ex.Message);
    }

    [Fact]
    public void Check_ProcessBaudRateZero_NamedAsTheLogNamesIt()
    {
        var problem = Assert.Single(JobRules.Check(ProcessSettings.Default with { GateBaudRate = 0 }, MachineLimits.Of(MachineProfile.Default)));

        Assert.Equal("gate baud rate 0: must be above 0", problem.Message);
    }

    [Fact]
    public void Problems_UnequalMicrosteps_RefusedWhenTheProfileIsRead()
    {
        // Once refused only by the two planners, when the first job was planned.
        var profile = MachineProfile.Default with { Y = MachineProfile.Default.Y with { MicrostepUm = 0.2 } };

        var problem = Assert.Single(MachineProfileValidator.Problems(profile));

        Assert.StartsWith("x.microstepUm 0.09921875 and y.microstepUm 0.2 must be equal", problem, StringComparison.Ordinal);
        Assert.Contains(problem, Assert.Throws<GeometryException>(() => GeometryResolver.Resolve(SizeSpec.Width(4), 10, 10, new OriginMm(0, 0), profile)).Message, StringComparison.Ordinal);
    }
}

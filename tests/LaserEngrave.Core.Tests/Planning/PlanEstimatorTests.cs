using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Core.Tests.Planning;

public class PlanEstimatorTests
{
    // Shared arithmetic, T-LA microstep 0.09921875 µm, 9600 baud 8N1 (10 bits per byte):
    //   Zaber round trip = 2 frames x 6 bytes x 10 bits / 9600 = 12.5 ms.
    //   Burn 1 mm/s = 10078.74 µsteps/s = 1075.07 units -> 1075 x 9.375 = 10078.125 µsteps/s.
    //   Travel 4 mm/s = 40314.96 µsteps/s = 4300.26 units -> 4300 x 9.375 = 40312.5 µsteps/s.
    //   Acceleration 50 mm/s² = 503937 µsteps/s² = 44.79 units -> 45 x 11250 = 506250 µsteps/s².
    //   "FREQ 1000\n" (10 bytes) + "OK FREQ 1000\n" (13 bytes) = 23 bytes = 23.958 ms.
    //   "OFF\n" (4 bytes) + "OK FREQ 0\n" (10 bytes) = 14 bytes = 14.583 ms.
    private const double RoundTrip = 0.0125;
    private const double BurnSpeed = 10078.125;
    private const double TravelSpeed = 40312.5;
    private const double Acceleration = 506250;
    private const double LaserOn = 23 * 10 / 9600.0;
    private const double LaserOff = 14 * 10 / 9600.0;

    private static PlanEstimator Optimized() => new(ProcessSettings.Default, PlanStrategy.Optimized, TestMasks.Microstep);

    [Fact]
    public void StartSeconds_SetsAccelerationAndSpeedOnBothAxes()
    {
        Assert.Equal(4 * RoundTrip, Optimized().StartSeconds, 12);
    }

    [Fact]
    public void ComputeStatistics_OneBurnRun_IsStartLaserOnSpeedChangeMoveAndLaserOff()
    {
        // Pixels 2..5 of a 10-pixel row at 1000 microsteps per pixel: one burn of 4000 microsteps.
        var mask = TestMasks.FromRows("..####....");
        var stats = new RasterPlan(mask, TestMasks.Geometry(mask)).ComputeStatistics(ProcessSettings.Default);

        // Start 4 x 12.5 ms = 50 ms; FREQ round trip 23.958 ms; X from travel to burn speed 12.5 ms;
        // motion: ramp distance v²/a = 10078.125² / 506250 = 200.6 < 4000, so a trapezoid of
        // v/a + d/v = 0.019907 + 0.396900 = 0.416807 s, plus the Move Absolute round trip 12.5 ms;
        // then OFF at the end 14.583 ms. Total 0.530348 s.
        const double Motion = (BurnSpeed / Acceleration) + (4000 / BurnSpeed);
        Assert.Equal(0.416807, Motion, 6);
        Assert.Equal(0.05 + LaserOn + RoundTrip + RoundTrip + Motion + LaserOff, stats.EngravingSeconds, 12);
        Assert.Equal(0.530348, stats.EngravingSeconds, 6);
        Assert.Equal(2, stats.LaserSwitches);
        Assert.Equal(1, stats.SpeedChanges);
    }

    [Fact]
    public void Add_DiagonalTravel_TakesTheLongerAxis()
    {
        // X 40000 and Y 10000 microsteps at 40312.5 µsteps/s: both longer than the ramp (v²/a = 3210 microsteps),
        // X takes v/a + 40000/v = 0.079630 + 0.992248 = 1.071878 s, Y 0.079630 + 0.248062 = 0.327692 s.
        // The axes already run at the travel speed and the laser is off: only the motion and its round trip count.
        var seconds = Optimized().Add(new Move(MoveKind.Travel, 0, 0, 40_000, 10_000, 0));
        Assert.Equal(RoundTrip + (TravelSpeed / Acceleration) + (40_000 / TravelSpeed), seconds, 12);
        Assert.Equal(1.084378, seconds, 6);
    }

    [Fact]
    public void Add_ShortMove_IsATriangle()
    {
        // 100 microsteps at the travel speed never reach it: t = 2 sqrt(d / a) = 2 sqrt(100 / 506250) = 28.109 ms.
        var seconds = Optimized().Add(new Move(MoveKind.Travel, 0, 0, 100, 0, 0));
        Assert.Equal(RoundTrip + (2 * Math.Sqrt(100 / Acceleration)), seconds, 12);
    }

    [Fact]
    public void Add_TravelAfterBurn_SwitchesTheLaserOffAndTheSpeedBack()
    {
        var estimator = Optimized();
        estimator.Add(new Move(MoveKind.Burn, 0, 0, 4000, 0, 0));
        var seconds = estimator.Add(new Move(MoveKind.Travel, 4000, 0, 8000, 0, 0));
        Assert.Equal(LaserOff + RoundTrip + RoundTrip + (TravelSpeed / Acceleration) + (4000 / TravelSpeed), seconds, 12);
        Assert.False(estimator.LaserOn);
        Assert.Equal(2, estimator.SpeedChanges);
    }

    [Fact]
    public void Add_OverscanAfterBurn_SwitchesTheLaserOffButKeepsTheBurnSpeed()
    {
        var estimator = Optimized();
        estimator.Add(new Move(MoveKind.Burn, 0, 0, 4000, 0, 0));
        var seconds = estimator.Add(new Move(MoveKind.Overscan, 4000, 0, 5000, 0, 0));
        Assert.Equal(LaserOff + RoundTrip + (BurnSpeed / Acceleration) + (1000 / BurnSpeed), seconds, 12);
        Assert.Equal(1, estimator.SpeedChanges);
    }

    [Fact]
    public void Add_Paper_RunsTravelsAtTheBurnSpeedWithoutSpeedChanges()
    {
        var estimator = new PlanEstimator(ProcessSettings.Default, PlanStrategy.Paper, TestMasks.Microstep);
        var travel = estimator.Add(new Move(MoveKind.Travel, 0, 0, 4000, 0, 0));
        estimator.Add(new Move(MoveKind.Burn, 4000, 0, 8000, 0, 0));
        Assert.Equal(RoundTrip + (BurnSpeed / Acceleration) + (4000 / BurnSpeed), travel, 12);
        Assert.Equal(0, estimator.SpeedChanges);
    }

    [Fact]
    public void Add_YOnlyMove_ChangesOnlyTheYSpeed()
    {
        var estimator = new PlanEstimator(ProcessSettings.Default with { TravelSpeedMmPerS = 2 }, PlanStrategy.Optimized, TestMasks.Microstep);
        estimator.Add(new Move(MoveKind.Burn, 0, 0, 4000, 0, 0));
        Assert.Equal(1, estimator.SpeedChanges);
        estimator.Add(new Move(MoveKind.Travel, 4000, 0, 4000, 1000, 1));
        Assert.Equal(1, estimator.SpeedChanges);
    }

    [Fact]
    public void Finish_LaserOff_AddsNothing()
    {
        var estimator = Optimized();
        Assert.Equal(0, estimator.Finish());
        Assert.Equal(estimator.StartSeconds, estimator.ElapsedSeconds);
    }

    [Fact]
    public void Constructor_FasterBauds_ShortensTheRoundTrips()
    {
        var estimator = new PlanEstimator(ProcessSettings.Default with { StageBaudRate = 19200 }, PlanStrategy.Optimized, TestMasks.Microstep);
        Assert.Equal(4 * RoundTrip / 2, estimator.StartSeconds, 12);
    }

    [Fact]
    public void Constructor_OtherGateStrings_CountTheirLength()
    {
        var gate = new LaserGateProfile { FrequencyCommand = "F{0}", LineTerminator = "\r\n" };
        var estimator = new PlanEstimator(ProcessSettings.Default, PlanStrategy.Optimized, TestMasks.Microstep, gate);
        var withGate = estimator.Add(new Move(MoveKind.Burn, 0, 0, 4000, 0, 0));
        var plain = Optimized().Add(new Move(MoveKind.Burn, 0, 0, 4000, 0, 0));

        // "F1000\r\n" (7) + "OK F1000\r\n" (10) = 17 bytes instead of 23.
        Assert.Equal(6 * 10 / 9600.0, plain - withGate, 12);
    }

    [Theory]
    [InlineData(0.0, 4.0)]
    [InlineData(1.0, double.NaN)]
    [InlineData(-1.0, 4.0)]
    public void Require_UnusableSpeed_RefusedByTheJobRulesBeforeAnyEstimate(double burn, double travel)
    {
        // The estimator takes only a process the job rules passed (issue 35: ProcessSettings.Validate, a second and weaker
        // rule set, is folded into them); the refusal names the speed as the app's field and the command line do.
        var process = ProcessSettings.Default with { BurnSpeedMmPerS = burn, TravelSpeedMmPerS = travel };

        var ex = Assert.Throws<PlanException>(() => Core.Jobs.JobRules.Require(process, MachineProfile.Default));

        Assert.Contains("speed", ex.Message, StringComparison.Ordinal);
        Assert.Contains("outside what the stage takes", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void SpeedMmPerS_PaperUsesTheBurnSpeedForEverything()
    {
        var process = ProcessSettings.Default with { BurnSpeedMmPerS = 1, TravelSpeedMmPerS = 3 };
        Assert.Equal(1, process.SpeedMmPerS(MoveKind.Travel, PlanStrategy.Paper));
        Assert.Equal(3, process.SpeedMmPerS(MoveKind.Travel, PlanStrategy.Optimized));
        Assert.Equal(1, process.SpeedMmPerS(MoveKind.Overscan, PlanStrategy.Optimized));
        Assert.Equal(1, process.SpeedMmPerS(MoveKind.Burn, PlanStrategy.Optimized));
    }

    [Fact]
    public void FromProfile_CopiesTheProfileDefaults()
    {
        var profile = MachineProfile.Default with { BurnSpeedMmPerS = 0.7, Gate = new LaserGateProfile { BaudRate = 19200 } };
        var process = ProcessSettings.FromProfile(profile);
        Assert.Equal(0.7, process.BurnSpeedMmPerS);
        Assert.Equal(19200, process.GateBaudRate);
    }
}

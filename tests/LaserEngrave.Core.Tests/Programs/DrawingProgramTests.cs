using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using static LaserEngrave.Core.Tests.Vectors.TestDrawings;

namespace LaserEngrave.Core.Tests.Programs;

/// <summary>A drawing's program: per stroke the travel to its run-up and its commands in device units, from a stop point, and the estimate over it.</summary>
public class DrawingProgramTests
{
    private static readonly TimedSwitching Timing = TimedSwitching.For(ProcessSettings.Default, MachineProfile.Default, MicrostepUm);

    // A line (one stroke, one path) and a square (split at its corners: four strokes of one path).
    private static VectorSchedule Schedule() => VectorMotion.Plan(
        VectorPlanner.Plan(
            SvgReader.Parse(Svg("<line x1=\"1\" y1=\"1\" x2=\"3\" y2=\"1\"/><rect x=\"5\" y=\"5\" width=\"2\" height=\"2\"/>", 20), "m.svg"),
            new VectorOptions { Origin = new OriginMm(5, 5) },
            MachineProfile.Default),
        Timing,
        MachineProfile.Default);

    [Fact]
    public void Steps_SmallDrawing_PerStrokeTheTravelToItsRunUpThenItsCommands()
    {
        var schedule = Schedule();
        var program = schedule.Program();
        var steps = program.Steps().ToList();

        Assert.Equal(schedule.Strokes.Count, program.StrokeCount);
        Assert.Equal(5, steps.Count);
        Assert.Equal(Enumerable.Range(0, 5), steps.Select(s => s.Index));
        Assert.Equal(schedule.Strokes, steps.Select(s => s.Stroke));

        // The first travel is the positioning, from wherever the stage stands; every later one from where the stroke before rests.
        Assert.Equal(new DrawingTravel(null, schedule.Strokes[0].RunUpStart, Timing.TravelSpeedData, false, false), steps[0].Travel);
        for (var k = 1; k < steps.Count; k++)
        {
            var before = schedule.Strokes[k - 1];
            Assert.Equal(new DrawingTravel(before.RestEnd, schedule.Strokes[k].RunUpStart, Timing.TravelSpeedData, before.Streams(VectorAxis.X), before.Streams(VectorAxis.Y)), steps[k].Travel);
        }

        // The line's one stroke ends its path; the square's four strokes end it at the last.
        Assert.Equal([true, false, false, false, true], steps.Select(s => s.LastOfPath));

        // The line along X (burned first) streams X only, in signed speed data: the run-up's speeds catch the spot up with
        // the model's grid, then it holds the burn speed until the run-out's and the stop.
        var line = steps[0].Stroke;
        Assert.True(line.Streams(VectorAxis.X) && !line.Streams(VectorAxis.Y));
        var held = line.Commands.Last(c => c.Kind == AxisCommandKind.Speed && c.AtSeconds < line.LaserOffSeconds);
        Assert.Equal(StageUnits.SignedSpeedData(Timing.BurnSpeed), held.SpeedData);
        Assert.Equal(AxisCommandKind.Stop, line.Commands[^1].Kind);
        Assert.Equal(Timing.AccelerationData, program.AccelerationData);
    }

    [Fact]
    public void Steps_FromAStopPoint_PositioningThenTheSameStepsAsTheWholeRun()
    {
        var program = Schedule().Program();
        var all = program.Steps().ToList();

        var resumed = program.Steps(2).ToList();

        // A resumed run reaches its stroke's run-up from where the stage stands (it reported it), then goes on as the whole run does.
        Assert.Equal(all[2] with { Travel = all[2].Travel with { From = null, StreamedX = false, StreamedY = false } }, resumed[0]);
        Assert.Equal(all.Skip(3), resumed.Skip(1));
        Assert.Empty(program.Steps(5));
        Assert.Throws<ArgumentOutOfRangeException>(() => program.Steps(-1));
    }

    [Fact]
    public void SecondsFrom_TheStepsAddedUp_SetupTravelsStrokesAndTheLastSwitchOff()
    {
        var schedule = Schedule();
        var program = schedule.Program();

        var expected = program.SetupSeconds;
        foreach (var step in program.Steps(1))
        {
            expected += program.TravelSeconds(step.Travel) + step.Stroke.NextArrivalSeconds;
        }

        Assert.Equal(expected + Timing.OffRoundTripSeconds, program.SecondsFrom(1), 12);
        Assert.Equal(schedule.EstimatedSeconds, program.SecondsFrom(0), 12);
        Assert.Equal(0, program.TravelSeconds(program.Steps(1).First().Travel));
        Assert.Equal(program.SetupSeconds + Timing.OffRoundTripSeconds, program.SecondsFrom(5), 12);
    }

    [Fact]
    public void TravelSeconds_AStreamedAxisAlreadyThere_StillMovedAndCounted()
    {
        var program = Schedule().Program();
        var at = new StagePoint(1000, 1000);

        var still = program.TravelSeconds(new DrawingTravel(at, at, Timing.TravelSpeedData, false, false));
        var streamed = program.TravelSeconds(new DrawingTravel(at, at, Timing.TravelSpeedData, true, false));

        Assert.Equal(0.0005, still, 12);
        Assert.Equal(Timing.StageCommandSeconds + Timing.StageReplySeconds + 0.0005, streamed, 12);
    }
}

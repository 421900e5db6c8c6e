using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>The run's accounting alone (<see cref="RunAccounting"/>): one count of rows and runs, the stop point, the progress.</summary>
public class RunAccountingTests
{
    private static readonly Move Travel0 = new(MoveKind.Travel, 0, 0, 100, 0, 0);
    private static readonly Move Burn0 = new(MoveKind.Burn, 100, 0, 200, 0, 0);
    private static readonly Move Burn1 = new(MoveKind.Burn, 200, 10, 100, 10, 1);

    [Fact]
    public void Completed_MovesOfTwoRows_CountsARowOnlyOnceTheNextHasStarted()
    {
        var accounting = new RunAccounting(rowsTotal: 2, runsTotal: 2);

        accounting.Completed(Travel0, 0);
        accounting.Completed(Burn0, 1);
        Assert.Equal((0, 1L), (accounting.RowsDone, accounting.RunsDone));

        accounting.Completed(Burn1, 2);
        Assert.Equal((1, 2L), (accounting.RowsDone, accounting.RunsDone));

        accounting.Ended(null, 2);
        Assert.Equal((2, 2L), (accounting.RowsDone, accounting.RunsDone));
        Assert.Equal(new RunStopPoint(2, 3), accounting.StopPoint(null));
    }

    [Fact]
    public void StopPoint_StageStoppedAtTheEndOfTheMoveOnIt_CountsThatMoveAsDone()
    {
        var accounting = new RunAccounting(2, 2);
        accounting.Completed(Travel0, 0);
        accounting.Executing(1, Burn0.Row, Burn0);

        Assert.Equal(new RunStopPoint(0, 2, 200, 0), accounting.StopPoint((200, 0)));
        Assert.Equal(new RunStopPoint(0, 1, 150, 0), accounting.StopPoint((150, 0)));
        Assert.Equal(new RunStopPoint(0, 1), accounting.StopPoint(null));
    }

    [Fact]
    public void CountDone_MovesBeforeAResumePoint_CountAsTheRunsCompletionsWould()
    {
        var resumed = new RunAccounting(2, 2);
        var run = new RunAccounting(2, 2);

        foreach (var (move, index) in new[] { (Travel0, 0L), (Burn0, 1L), (Burn1, 2L) })
        {
            resumed.CountDone(move.Kind, move.Row);
            run.Completed(move, index);
        }

        Assert.Equal((run.RowsDone, run.RunsDone), (resumed.RowsDone, resumed.RunsDone));
    }

    [Fact]
    public void Snapshot_ResumedTimedRun_CountsWhatWasDoneBeforeAndKeepsToTheClock()
    {
        var accounting = new RunAccounting(2, 2) { EstimateTotal = 100, EstimateBefore = 40 };

        var before = accounting.Snapshot(RunState.Running, TimeSpan.FromSeconds(5), null, byClock: true, 1, 2, laserOn: false);
        var during = accounting.Snapshot(RunState.Running, TimeSpan.FromSeconds(35), 30, byClock: true, 1, 2, laserOn: true);
        var beyond = accounting.Snapshot(RunState.Running, TimeSpan.FromSeconds(95), 90, byClock: true, 1, 2, laserOn: true);

        Assert.Equal(40, before.Percent, 9);
        Assert.Equal(TimeSpan.FromSeconds(60), before.Remaining);
        Assert.Equal(70, during.Percent, 9);
        Assert.Equal(30, during.Remaining.TotalSeconds, 9);
        Assert.Equal(100, beyond.Percent, 9);
        Assert.Equal(TimeSpan.Zero, beyond.Remaining);
        Assert.True(during.LaserOn);
        Assert.Equal((1L, 2L), (during.XMicrosteps, during.YMicrosteps));
    }

    [Fact]
    public void StrokeDone_LastStrokeOfAPath_CountsThePathAsARun()
    {
        var accounting = new RunAccounting(3, 2);
        accounting.DoneBefore(1, 0);

        accounting.StrokeDone(1, lastOfPath: true);
        accounting.StrokeDone(2, lastOfPath: false);

        Assert.Equal((3, 1L), (accounting.RowsDone, accounting.RunsDone));
        Assert.Equal(3, accounting.StopPoint(null).MoveIndex);
    }
}

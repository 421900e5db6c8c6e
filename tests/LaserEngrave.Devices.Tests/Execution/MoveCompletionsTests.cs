using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>A timed run's moves reported done (<see cref="MoveCompletions"/>): in plan order, a burn run once its switch-on is acknowledged.</summary>
public class MoveCompletionsTests
{
    private static readonly Move Travel0 = new(MoveKind.Travel, 0, 0, 100, 0, 0);
    private static readonly Move Burn1 = new(MoveKind.Burn, 100, 0, 200, 0, 0);
    private static readonly Move Travel2 = new(MoveKind.Travel, 200, 0, 200, 10, 0);

    [Fact]
    public void Up_SwitchOnNotAcknowledged_HoldsItAndEveryLaterMove()
    {
        var done = new List<long>();
        var completions = new MoveCompletions((_, i) => done.Add(i));
        var switchOn = new TaskCompletionSource();

        completions.Up(Travel0, 0, null);
        completions.Up(Burn1, 1, switchOn.Task);
        completions.Up(Travel2, 2, null);

        Assert.Equal([0L], done);
    }

    [Fact]
    public void Acknowledged_SwitchOnAcknowledgedSince_ReportsTheHeldMovesInOrder()
    {
        var done = new List<(Move Move, long Index)>();
        var completions = new MoveCompletions((m, i) => done.Add((m, i)));
        var switchOn = new TaskCompletionSource();
        completions.Up(Travel0, 0, null);
        completions.Up(Burn1, 1, switchOn.Task);
        completions.Up(Travel2, 2, null);

        switchOn.SetResult();
        completions.Acknowledged();

        Assert.Equal([(Travel0, 0L), (Burn1, 1L), (Travel2, 2L)], done);
    }

    [Fact]
    public void Acknowledged_SwitchOnRefused_NeverReportsTheRun()
    {
        // A refused switch-on burned nothing: the run is not counted, and the stop point stays before it.
        var done = new List<long>();
        var completions = new MoveCompletions((_, i) => done.Add(i));
        var switchOn = new TaskCompletionSource();
        completions.Up(Burn1, 1, switchOn.Task);

        switchOn.SetException(new InvalidOperationException("ERR"));
        completions.Acknowledged();

        Assert.Empty(done);
    }

    [Fact]
    public void StartAt_AResumedRun_QueuesNoMoveBeforeItsFirst()
    {
        var done = new List<long>();
        var completions = new MoveCompletions((_, i) => done.Add(i));

        completions.StartAt(2);
        completions.Up(Burn1, 1, null);
        completions.Up(Travel2, 2, null);

        Assert.Equal([2L], done);
    }

    [Fact]
    public void UpTo_AStrokeAskedTwice_ReportsEachOfItsMovesOnce()
    {
        var job = TestJobs.FromAsset("qr-code.bmp", 2, PlanOptions.Default, ProcessSettings.Default);
        var stroke = job.Program().Steps().Select(s => s.Stroke).First(s => s is { RunCount: > 0 })!;
        var (_, firstBurn) = stroke.RunAt(0);
        var done = new List<long>();
        var completions = new MoveCompletions((_, i) => done.Add(i));

        completions.UpTo(stroke, firstBurn - 1, null);
        completions.UpTo(stroke, firstBurn, null);
        completions.UpTo(stroke, stroke.FirstMoveIndex + stroke.MoveCount - 1, null);

        Assert.Equal([.. Enumerable.Range(0, stroke.MoveCount).Select(i => stroke.FirstMoveIndex + i)], done);
    }
}

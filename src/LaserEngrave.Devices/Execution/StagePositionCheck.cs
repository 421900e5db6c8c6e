using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Planning;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>What <see cref="StagePositionCheck"/> asks of the run whose strokes it checks.</summary>
internal interface IStagePositionCheckRun
{
    /// <summary>Seconds since the engraving started, on the run's clock.</summary>
    double RunSeconds { get; }

    /// <summary>The latency spread the run assumes, in times the profile's.</summary>
    double LatencyScale { get; }

    /// <summary>Throws when the run was aborted.</summary>
    void ThrowIfAborted();

    /// <summary>Ends the run at a fault, laser off first; returns the exception to throw.</summary>
    DeviceException Fault(string reason, bool recoverable);

    /// <summary>Waits until <paramref name="seconds"/> run seconds.</summary>
    Task DelayUntilAsync(double seconds, CancellationToken token);

    /// <summary>Watches a reply against its expected arrival (<see cref="ReplyWatch.Watch"/>).</summary>
    void Watch(Task reply, double expectedSeconds, string what);

    /// <summary>How much later than <paramref name="plannedWrite"/> a command's write completed; 0 when on time or unknown.</summary>
    Task<double> WrittenLateAsync(Task<long?> lineWritten, double plannedWrite);

    /// <summary>Whether <paramref name="task"/> completes by <paramref name="seconds"/> run seconds.</summary>
    Task<bool> CompletesByAsync(Task task, double seconds, CancellationToken token);

    /// <summary>A flown gap's speed-up has been sent: from here the stroke's plan holds that gap.</summary>
    void GapFlown();

    /// <summary>The latencies spread this wide, in times the profile's (what a run that goes on from here assumes).</summary>
    void LatencySeen(double scale);
}

/// <summary>
/// Where the X axis is against a stroke's plan, asked at the two places the laser waits for it (docs/execution.md): at
/// a stroke's start, before its first switch-on (every earlier move reported, the stage seen moving), and after each
/// flown gap (the gap flown at the travel speed, then the position that puts the next switchings back on their edges).
/// A reply too late, missing or outside its window ends the run with the laser off, most of them as a timing doubt.
/// </summary>
internal sealed class StagePositionCheck(IStage stage, MotionData motion, long travelXMicrosteps, IStagePositionCheckRun run)
{
    private readonly IStage _stage = stage;
    private readonly MotionData _motion = motion;
    private readonly long _travelXMicrosteps = travelXMicrosteps;
    private readonly IStagePositionCheckRun _run = run;

    /// <summary>
    /// Flies a gap (docs/execution.md, "Flown gaps"): the travel speed set just after the exit edge, the burn speed set back,
    /// then a position query once the stage is surely at the burn speed again; returns the query.
    /// </summary>
    public async Task<FlownQuery> FlyGapAsync(StrokePlan.Bump bump, double start, TimedSwitching timing, CancellationToken token)
    {
        var upWrite = start + bump.SpeedUpArrival - timing.StageCommandSeconds;
        await _run.DelayUntilAsync(upWrite, token);
        _run.ThrowIfAborted();
        var upLate = _run.RunSeconds - upWrite;
        _run.Watch(_stage.X.SetTargetSpeedAsync(_motion.TravelSpeedData, token), GateSwitching.Sent(start + bump.SpeedUpArrival, _run.RunSeconds, timing) + timing.StageReplySeconds, "Set Target Speed (X, a flown gap)");
        var upWritten = _stage.LineWritten;
        _run.GapFlown();
        var downWrite = start + bump.SpeedDownArrival - timing.StageCommandSeconds;
        await _run.DelayUntilAsync(downWrite, token);

        // A write that completed late (a computer stalled before it) left that late, whatever the clock said before it.
        upLate = Math.Max(upLate, await _run.WrittenLateAsync(upWritten, upWrite));
        var downLate = _run.RunSeconds - downWrite;
        _run.Watch(_stage.X.SetTargetSpeedAsync(_motion.BurnSpeedData, token), GateSwitching.Sent(start + bump.SpeedDownArrival, _run.RunSeconds, timing) + timing.StageReplySeconds, "Set Target Speed (X, after a flown gap)");
        downLate = Math.Max(downLate, await _run.WrittenLateAsync(_stage.LineWritten, downWrite));

        // The query goes once the stage is surely back at the burn speed: never sooner after the speed-down than planned,
        // and later still when the speed-down left late against the speed-up (a busy computer): held longer, the bump
        // peaks higher and takes that much longer to come back down, and a query before that would find the stage still
        // fast, take it for behind its plan, and the laser would come on early.
        var hold = bump.SpeedDownArrival - bump.SpeedUpArrival;
        var longer = GateSwitching.Later(0, downLate) - GateSwitching.Later(0, upLate);
        var rampDown = longer > 0 ? (Rise(timing, hold + longer) - Rise(timing, hold)) / timing.Acceleration : 0;
        var queryWrite = start + bump.QueryArrival - timing.StageCommandSeconds;
        await _run.DelayUntilAsync(Math.Max(queryWrite, _run.RunSeconds + (bump.QueryArrival - bump.SpeedDownArrival) + rampDown), token);
        var queryLate = _run.RunSeconds - queryWrite;
        var queryStamped = _run.RunSeconds;
        var query = Arrival(_stage.X.GetPositionAsync(token));
        var queryWrittenLate = await _run.WrittenLateAsync(_stage.LineWritten, queryWrite);
        queryLate = Math.Max(queryLate, queryWrittenLate);

        // Its round trip counts from the write's completion: a stall before the write is the host's, not the reply's.
        return new FlownQuery(query, Math.Max(queryStamped, queryWrite + queryWrittenLate), GateSwitching.Later(0, upLate), GateSwitching.Later(0, downLate), GateSwitching.Later(0, queryLate));
    }

    /// <summary>How far above the burn speed a bump held <paramref name="hold"/> s rises (<see cref="TimedSwitching.FlyGain"/>'s dV).</summary>
    private static double Rise(TimedSwitching timing, double hold) =>
        Math.Min(timing.Acceleration * Math.Max(0, hold), Math.Max(0, timing.TravelSpeed - timing.BurnSpeed));

    /// <summary>A flown gap's position query, and how late (s) the host wrote the speed-up, the speed-down and the query.</summary>
    public sealed record FlownQuery(Answered<long> Query, double WrittenSeconds, double UpLate, double DownLate, double QueryLate);

    /// <summary>A reply and when it came in (run seconds; NaN until then), so that it is judged by its round trip as well as by what it says.</summary>
    public sealed class Answered<T>(Task<T> task)
    {
        public Task<T> Task { get; } = task;

        public double Seconds { get; set; } = double.NaN;
    }

    /// <summary>Stamps a reply's arrival on the run clock when its task completes (before anything awaiting it runs).</summary>
    public Answered<T> Arrival<T>(Task<T> task)
    {
        var arrived = new Answered<T>(task);
        _ = task.ContinueWith(_ => arrived.Seconds = _run.RunSeconds, CancellationToken.None, TaskContinuationOptions.ExecuteSynchronously, TaskScheduler.Default);
        return arrived;
    }

    /// <summary>
    /// A position reply that came back too late to locate the stage (issue 34): its round trip from <paramref name="written"/>
    /// past what the links allow (<paramref name="frames"/> frames on the wire each way, both adapters and their spreads, a
    /// margin), so when the axis answered is not known and its position says nothing of where the stage is against its
    /// plan. A timing doubt with the laser off, never "ahead of plan".
    /// </summary>
    private void ThrowIfReplyTooLate<T>(Answered<T> reply, double written, int frames, TimedSwitching timing, string what)
    {
        var roundTrip = reply.Seconds - written;
        var expected = timing.StageAdapterSeconds + (frames * timing.FrameSeconds) + timing.StageReplySeconds;
        var allowed = expected + (4 * timing.StageJitterSeconds) + ReplyMarginSeconds;
        if (roundTrip > allowed)
        {
            throw _run.Fault(
                string.Create(CultureInfo.InvariantCulture, $"the X axis' reply to {what} came back {Units.SecondsToMs(roundTrip):0.0} ms after it was written ({Units.SecondsToMs(expected):0.0} ms expected): too late to locate the stage, so the laser stays off"),
                recoverable: true);
        }
    }

    // What a position reply's round trip may exceed its links' spread by (the host's own reaction to the reply).
    private const double ReplyMarginSeconds = 0.002;

    /// <summary>
    /// After a flown gap, before the next switch-on: the position query's answer says how far ahead of its plan the stage
    /// is (the speed changes' latencies); returns the time shift that puts the next switchings back on their edges.
    /// </summary>
    public async Task<double> MeasureFlownGapAsync(StrokePlan.Bump bump, FlownQuery flown, long start, int direction, TimedSwitching timing, double onWrite, CancellationToken token)
    {
        var query = flown.Query.Task;
        if (!await _run.CompletesByAsync(query, onWrite, token) || !query.IsCompletedSuccessfully)
        {
            throw _run.Fault("the X axis did not answer the position query after a flown gap before the laser was to come on", recoverable: true);
        }

        ThrowIfReplyTooLate(flown.Query, flown.WrittenSeconds, 1, timing, "the position query after a flown gap");

        // A host late to write (a loaded computer) held the bump longer or shorter and asked later: where the stage then is.
        var hold = bump.SpeedDownArrival - bump.SpeedUpArrival;
        var gainedMore = timing.FlyGain(hold + flown.DownLate - flown.UpLate) - timing.FlyGain(hold);
        var expected = bump.ExpectedOffset + (timing.BurnSpeed * flown.QueryLate) + gainedMore;
        var ahead = ((query.Result - start) * direction) - expected;
        if (Math.Abs(ahead) > bump.MaxErrorMicrosteps + 1)
        {
            // The latencies spread wider than assumed. One check sees one or two draws of them and rarely their largest, so
            // the run that goes on from here assumes twice what this one found (RunResult.LatencyScale).
            _run.LatencySeen(Math.Min(RunPreflight.MaxLatencyScale, 2 * _run.LatencyScale * Math.Abs(ahead) / Math.Max(bump.MaxErrorMicrosteps, 1)));

            throw _run.Fault(string.Create(
                System.Globalization.CultureInfo.InvariantCulture,
                $"the X axis reported {query.Result} microsteps after a flown gap, {ahead:0} from its plan (at most {bump.MaxErrorMicrosteps:0} expected): it is not moving as planned, so the laser stays off"),
                recoverable: true);
        }

        // What the bump gained beyond its plan (its speed commands' real interval) is the stage ahead of its plan as surely as
        // what the query found: every later switching comes that much sooner. Asking later is not: it is only time passing.
        return -(ahead + gainedMore) / timing.BurnSpeed;
    }

    /// <summary>Before the first switch-on of a stroke: every earlier move has reported its end, and the position query shows the stage on its way.</summary>
    public async Task ConfirmMovingAsync(IReadOnlyList<ReplyWatch.Watched> earlier, Answered<long> arrived, double moveWritten, long start, int direction, TimedSwitching timing, double onWrite, CancellationToken token, double pollLate = 0)
    {
        var poll = arrived.Task;
        foreach (var watched in earlier)
        {
            // A move whose end is never reported is settled by the next move of its axis reporting its own.
            if (!await _run.CompletesByAsync(watched.Settled(), onWrite, token))
            {
                throw _run.Fault($"the stage had not reported {watched.What} when the laser was to come on", recoverable: true);
            }
        }

        if (!await _run.CompletesByAsync(poll, onWrite, token))
        {
            throw _run.Fault("the X axis did not answer the position query before the laser was to come on", recoverable: true);
        }

        long position;
        try
        {
            position = await poll;
        }
        catch (DeviceException ex)
        {
            throw _run.Fault($"the X axis did not answer the position query before the laser was to come on: {ex.Message}", recoverable: false);
        }

        // The stroke's Move Absolute and its query together: the query's frame leaves behind the move's.
        ThrowIfReplyTooLate(arrived, moveWritten + pollLate, 2, timing, "the position query after a stroke's Move Absolute");

        // The query arrives one frame after the move: the stage has accelerated that long, give or take both latencies.
        var a = timing.Acceleration;
        var earliest = Math.Max(0, timing.FrameSeconds + pollLate - (2 * timing.StageJitterSeconds));
        var latest = timing.FrameSeconds + pollLate + (2 * timing.StageJitterSeconds);
        var moved = (position - start) * direction;
        var least = Math.Max(1, Math.Floor(0.5 * a * earliest * earliest / 2));
        var most = Math.Ceiling(0.5 * a * latest * latest) + 2;
        if (moved < least && moved >= 0 && _run.RunSeconds + timing.FrameSeconds + timing.StageReplySeconds + (2 * timing.StageJitterSeconds) < onWrite)
        {
            // Not yet seen moving (the query overtook the move's start on a late device, or on a simulator on the wall
            // clock): ask once more while there is time; the laser stays off until it has been seen moving.
            var againWritten = _run.RunSeconds;
            var againArrived = Arrival(_stage.X.GetPositionAsync(token));
            var again = againArrived.Task;
            if (await _run.CompletesByAsync(again, onWrite, token) && again.IsCompletedSuccessfully)
            {
                ThrowIfReplyTooLate(againArrived, againWritten, 1, timing, "a second position query at a stroke's start");
                position = again.Result;
                moved = (position - start) * direction;
                least = 1;
                most = Math.Abs(_travelXMicrosteps);
            }
        }

        if (moved < least || moved > most)
        {
            throw _run.Fault($"the X axis reported {position} microsteps just after starting its stroke, not {start + (direction * least)}..{start + (direction * most)}: it is not moving as planned, so the laser stays off", recoverable: false);
        }
    }
}

using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using NSubstitute.Core;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>What a faked <see cref="Services.IRunService"/> hands back: the session's result and its progress reports.</summary>
internal static class SessionResults
{
    /// <summary>What the session returns for a run that ended with <paramref name="run"/> (or <paramref name="error"/>): its record, logged through its writer, as the session does.</summary>
    public static EngraveResult Ended(EngraveSession session, RunResult? run, Exception? error = null)
    {
        var record = (session.Drawing is { } drawing ? RunRecord.ForDrawing(drawing, new string('0', 64), DateTimeOffset.UnixEpoch) : RunRecord.ForJob(session.Job!, new string('0', 64), DateTimeOffset.UnixEpoch)) with
        {
            Notes = session.Options.Notes,
            SampleId = session.Options.SampleId,
            RepeatOf = session.Options.RepeatOf,
            Resumed = session.Options.ResumeFrom is not null,
            Passes = session.Passes,
        };
        record = RunRecords.Complete(record, run, error, "fake", "fake", DateTimeOffset.UnixEpoch.AddSeconds(12), TimeSpan.FromSeconds(12)) with
        {
            PassesDone = session.Passes > 1 ? (run?.Outcome == RunOutcome.Completed ? session.Passes : 0) : null,
        };
        return new EngraveResult(record, run, error, session.Options.Log?.Write(record), null);
    }

    /// <summary>A fake run that reports nothing and ends with <paramref name="run"/>.</summary>
    public static Func<CallInfo, Task<EngraveResult>> Ends(RunResult run) => c => Task.FromResult(Ended(c.Arg<EngraveSession>(), run));

    /// <summary>A pass's result with the given outcome and made-up figures (5 rows, 7 runs).</summary>
    public static RunResult Result(RunOutcome outcome, string? fault = null) => new()
    {
        Outcome = outcome,
        FaultMessage = fault,
        LaserOffConfirmed = true,
        StartedAt = DateTimeOffset.UnixEpoch,
        EndedAt = DateTimeOffset.UnixEpoch.AddSeconds(12),
        EngravingDuration = TimeSpan.FromSeconds(10),
        EstimatedSeconds = 11,
        LaserOnSeconds = 4,
        RowsDone = 5,
        RowsTotal = 5,
        RunsDone = 7,
        RunsTotal = 7,
    };

    /// <summary>A session's report: the state, the pass, moves done of all, and the pass's figures.</summary>
    public static EngraveProgress Report(RunState state, long movesDone, long movesTotal, int rowsDone, int rowsTotal, int pass = 1, int passes = 1, long x = 0, long y = 0, bool laserOn = false, double remainingSeconds = 0) =>
        new(state, pass, passes, movesDone, movesTotal, false, new RunProgress(state, rowsDone, rowsTotal, 0, 0, 0, TimeSpan.Zero, TimeSpan.FromSeconds(remainingSeconds), x, y, laserOn));
}

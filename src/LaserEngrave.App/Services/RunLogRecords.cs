using System.Globalization;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Execution;
using LogOutcome = LaserEngrave.Core.Logging.RunOutcome;
using LogStopPoint = LaserEngrave.Core.Logging.RunStopPoint;
using RunOutcome = LaserEngrave.Devices.Execution.RunOutcome;

namespace LaserEngrave.App.Services;

/// <summary>Fills a run log record from how the run ended, as the command line's engrave does.</summary>
internal static class RunLogRecords
{
    public static RunRecord Finish(RunRecord record, RunResult? run, Exception? error, IMachineConnection connection, DateTimeOffset endedAt)
    {
        if (run is null)
        {
            var outcome = error switch
            {
                PreflightException => LogOutcome.Refused,
                OperationCanceledException => LogOutcome.Aborted,
                _ => LogOutcome.Failed,
            };
            return record with
            {
                EndedAt = endedAt,
                ActualSeconds = (endedAt - record.StartedAt).TotalSeconds,
                Outcome = outcome,
                Fault = new RunFault(error?.Message.ReplaceLineEndings(" ") ?? "the run ended without a result", outcome == LogOutcome.Refused ? "preflight" : error?.GetType().Name),
            };
        }

        var port = connection.Description;
        return record with
        {
            EndedAt = endedAt,
            Outcome = run.Outcome switch
            {
                RunOutcome.Completed => LogOutcome.Completed,
                RunOutcome.Aborted => LogOutcome.Aborted,
                _ => LogOutcome.Failed,
            },
            Fault = run.Outcome == RunOutcome.Completed
                ? null
                : new RunFault(run.FaultMessage ?? "no reason given", run.Outcome == RunOutcome.Aborted ? "aborted" : null, run.LaserOffConfirmed),
            StoppedAt = run.StopPoint is { } stop ? new LogStopPoint(stop.Row, stop.MoveIndex, stop.XMicrosteps, stop.YMicrosteps) : null,
            Devices = run.Machine is { } machine
                ?
                [
                    new RunDevice("x axis", port, string.Create(CultureInfo.InvariantCulture, $"device {machine.X.DeviceNumber}, ID {machine.X.DeviceId}"), machine.X.FirmwareText),
                    new RunDevice("y axis", port, string.Create(CultureInfo.InvariantCulture, $"device {machine.Y.DeviceNumber}, ID {machine.Y.DeviceId}"), machine.Y.FirmwareText),
                    new RunDevice("laser gate", port, machine.Gate, machine.Gate.Split(' ', StringSplitOptions.RemoveEmptyEntries).LastOrDefault() ?? machine.Gate),
                ]
                : [],
            EstimatedSeconds = run.EstimatedSeconds,
            ActualSeconds = run.Duration.TotalSeconds,
            EngravingSeconds = run.EngravingDuration.TotalSeconds,
            LaserOnSeconds = run.LaserOnSeconds,
            RowsDone = run.RowsDone,
            RowsTotal = run.RowsTotal,
            RunsDone = run.RunsDone,
            RunsTotal = run.RunsTotal,
        };
    }
}

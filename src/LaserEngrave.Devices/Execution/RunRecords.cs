using System.Globalization;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Devices.Execution;

/// <summary>Completes a run's log record from how the run ended, so the command line and the app log a run alike.</summary>
public static class RunRecords
{
    /// <summary>The record of <paramref name="record"/>'s job after the run: outcome, fault, stop point, devices, times and counts.</summary>
    /// <param name="record">The record made before the run (<see cref="RunRecord.ForJob"/>).</param>
    /// <param name="run">The executor's result; null when the run ended without one (<paramref name="error"/> says why).</param>
    /// <param name="error">What ended the run without a result: a preflight refusal, a cancellation or a failure.</param>
    /// <param name="stagePort">The stage's port, as the log should name it.</param>
    /// <param name="laserPort">The laser gate's port, as the log should name it.</param>
    /// <param name="endedAt">When the run ended.</param>
    /// <param name="elapsed">The run's time on the machine's clock (virtual on the simulator), for a run that ended without a result.</param>
    public static RunRecord Complete(RunRecord record, RunResult? run, Exception? error, string stagePort, string laserPort, DateTimeOffset endedAt, TimeSpan elapsed)
    {
        ArgumentNullException.ThrowIfNull(record);
        if (run is null)
        {
            var outcome = error switch
            {
                PreflightException => RunOutcome.Refused,
                OperationCanceledException => RunOutcome.Aborted,
                _ => RunOutcome.Failed,
            };
            return record with
            {
                EndedAt = endedAt,
                ActualSeconds = elapsed.TotalSeconds,
                Outcome = outcome,
                Fault = new RunFault(error?.Message.ReplaceLineEndings(" ") ?? "the run ended without a result", outcome == RunOutcome.Refused ? "preflight" : error?.GetType().Name),
            };
        }

        return record with
        {
            EndedAt = endedAt,
            Outcome = run.Outcome,
            Fault = run.Outcome == RunOutcome.Completed
                ? null
                : new RunFault(run.FaultMessage ?? "no reason given", run.Outcome == RunOutcome.Aborted ? "aborted" : null, run.LaserOffConfirmed, run.LaserOffBy, run.BurstEndedItself),
            StoppedAt = run.StopPoint,
            Devices = run.Machine is { } machine
                ?
                [
                    new RunDevice("x axis", stagePort, string.Create(CultureInfo.InvariantCulture, $"device {machine.X.DeviceNumber}, ID {machine.X.DeviceId}"), machine.X.FirmwareText),
                    new RunDevice("y axis", stagePort, string.Create(CultureInfo.InvariantCulture, $"device {machine.Y.DeviceNumber}, ID {machine.Y.DeviceId}"), machine.Y.FirmwareText),
                    new RunDevice("laser gate", laserPort, machine.Gate, GateFirmware(machine.Gate)),
                ]
                : [],
            EstimatedSeconds = run.EstimatedSeconds,
            EstimatedEngravingSeconds = run.EstimatedEngravingSeconds,
            ActualSeconds = run.Duration.TotalSeconds,
            EngravingSeconds = run.EngravingDuration.TotalSeconds,
            LaserOnSeconds = run.LaserOnSeconds,
            LateSwitches = run.LateSwitches,
            GuardScale = run.GuardScale > 1 ? run.GuardScale : null,
            RowsDone = run.RowsDone,
            RowsTotal = run.RowsTotal,
            RunsDone = run.RunsDone,
            RunsTotal = run.RunsTotal,
        };
    }

    /// <summary>The gate identifies itself as "NAME VERSION"; the last word is its firmware.</summary>
    private static string GateFirmware(string identity)
    {
        var words = identity.Split(' ', StringSplitOptions.RemoveEmptyEntries);
        return words.Length > 0 ? words[^1] : "unknown";
    }
}

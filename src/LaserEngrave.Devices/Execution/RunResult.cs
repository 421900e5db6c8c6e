using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Devices.Abstractions;

namespace LaserEngrave.Devices.Execution;

/// <summary>What the devices said about themselves in preflight, for the run log.</summary>
/// <param name="X">The X axis.</param>
/// <param name="Y">The Y axis.</param>
/// <param name="Gate">The gate's identification text ("PICGATE SIM-1.0").</param>
public sealed record MachineIdentity(AxisIdentity X, AxisIdentity Y, string Gate);

/// <summary>How a run ended, with everything the run log needs.</summary>
public sealed record RunResult
{
    public required RunOutcome Outcome { get; init; }

    /// <summary>One line: what went wrong (null when completed; "aborted by the operator" when aborted).</summary>
    public string? FaultMessage { get; init; }

    /// <summary>Where the run stopped; give it to <see cref="RunOptions.ResumeFrom"/> to finish the job (null when completed).</summary>
    public RunStopPoint? StopPoint { get; init; }

    /// <summary>
    /// The run failed on a timing doubt that burned nothing wrongly: the laser was off (confirmed) in a flown gap or before
    /// a stroke's first switch-on, no burn run was cut, and the fault says only that a position query answered too late,
    /// or found the stage too far from its plan, for the next switch-on to be timed, or that a stage reply did not come
    /// within its grace (a busy computer, a reply lost). It may go on from <see cref="StopPoint"/> at once, as a resume
    /// would: the resumed run's preflight asks every device again, so a stage that is gone ends it there.
    /// </summary>
    public bool Recoverable { get; init; }

    /// <summary>
    /// The latency spread, in times the profile's, that the run assumed or its checks showed (twice the largest ratio a
    /// failed flown-gap check found): what a run going on from this one must assume (<see cref="RunOptions.LatencyScale"/>).
    /// </summary>
    public double LatencyScale { get; init; } = 1;

    /// <summary>
    /// The scale the run's guards, margins and checks were widened by (the latency spread it timed itself with, in times the
    /// profile's; 1: as the profile says): wider guards aim every switching further inside its run, so lines come out
    /// shorter. For the log, the summary and the app.
    /// </summary>
    public double GuardScale { get; init; } = 1;

    /// <summary>False when the laser could not be confirmed off at the end (the gate did not answer any attempt).</summary>
    public required bool LaserOffConfirmed { get; init; }

    /// <summary>Which command the gate acknowledged to confirm the laser off after a fault or an abort (None: none did); null when completed.</summary>
    public LaserOffPath? LaserOffBy { get; init; }

    public required DateTimeOffset StartedAt { get; init; }

    public required DateTimeOffset EndedAt { get; init; }

    /// <summary>The whole run on its clock (virtual time on the in-process simulator): preflight, positioning, plan, pauses.</summary>
    public TimeSpan Duration => EndedAt - StartedAt;

    /// <summary>The part the estimate models: from setting speed and acceleration at the plan's first position to the end, pauses left out.</summary>
    public required TimeSpan EngravingDuration { get; init; }

    /// <summary>Estimated duration of the whole run: preflight (with homing if it homed), the travel to the first move and <see cref="EstimatedEngravingSeconds"/>, s.</summary>
    public required double EstimatedSeconds { get; init; }

    /// <summary>Estimated duration of the moves this run was to execute (all of them, or those after the resume point), s.</summary>
    public double EstimatedEngravingSeconds { get; init; }

    /// <summary>Time the laser was on (from each switch-on's acknowledgement to the switch-off's), s.</summary>
    public required double LaserOnSeconds { get; init; }

    /// <summary>Switchings the computer sent late but within the profile's edge tolerance (docs/execution.md, "The burst"): how many, and the latest as µm at the burn speed.</summary>
    public LateSwitches? LateSwitches { get; init; }

    /// <summary>Whether the burn run's burst had stopped the laser by itself before a switch-off was refused or went unanswered.</summary>
    public bool BurstEndedItself { get; init; }

    /// <summary>Visited rows finished over the whole plan (with those done before a resume).</summary>
    public required int RowsDone { get; init; }

    public required int RowsTotal { get; init; }

    /// <summary>Burn runs finished over the whole plan (with those done before a resume).</summary>
    public required long RunsDone { get; init; }

    public required long RunsTotal { get; init; }

    /// <summary>The devices' identities (firmware), null when preflight did not get that far.</summary>
    public MachineIdentity? Machine { get; init; }
}

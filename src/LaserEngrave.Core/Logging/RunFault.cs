namespace LaserEngrave.Core.Logging;

/// <summary>What stopped a run that did not complete, and whether the laser was confirmed off afterwards.</summary>
/// <param name="Message">The one-line error, as the operator saw it.</param>
/// <param name="Kind">The kind of fault, e.g. "timeout", "port lost", "gate silent", "aborted"; free text from the executor.</param>
/// <param name="LaserOffConfirmed">Whether the gate acknowledged the laser switching off after the fault.</param>
/// <param name="LaserOffBy">Which command the gate acknowledged to confirm it off (<see cref="LaserOffPath.None"/>: none did); null in older logs.</param>
/// <param name="BurstEnded">Whether the burn run's burst had already stopped the laser by itself (the gate counts its pulses) when a switch-off was refused or went unanswered.</param>
public sealed record RunFault(string Message, string? Kind = null, bool LaserOffConfirmed = true, LaserOffPath? LaserOffBy = null, bool BurstEnded = false);

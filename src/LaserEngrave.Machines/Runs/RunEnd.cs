using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Machines.Runs;

/// <summary>How a run ended: the session's result (record, log files, error) and what it did to the sample counter.</summary>
/// <param name="Result">The record, the passes' result or error, and where the log went.</param>
/// <param name="NextMarkNumber">The sample counter's next number once a completed run of marks advanced it; null when it did not.</param>
/// <param name="CounterProblem">Why the counter could not be advanced after a completed run of marks (the run is logged all the same); null otherwise.</param>
public sealed record RunEnd(EngraveResult Result, int? NextMarkNumber, string? CounterProblem);

namespace LaserEngrave.Core.Logging;

/// <summary>
/// A timing doubt the run went on from: the laser was off (in a flown gap, or before a stroke's first switch-on) when a
/// position query answered too late, or found the stage too far from its plan, for the next switch-on to be timed; the
/// pass went on from its stop point, as a resume would.
/// </summary>
/// <param name="Pass">The pass it happened in, 1-based.</param>
/// <param name="Fault">The doubt, one line, as a fault would have said it.</param>
/// <param name="MoveIndex">The move the pass went on from.</param>
/// <param name="Row">That move's image row.</param>
public sealed record RunRecovery(int Pass, string Fault, long MoveIndex, int Row);

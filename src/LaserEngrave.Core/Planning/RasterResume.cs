namespace LaserEngrave.Core.Planning;

/// <summary>Where a raster program goes on from a stop point (<see cref="RasterProgram.ResumeAt"/>), and what was done before it.</summary>
/// <param name="Stop">The stop point.</param>
/// <param name="FirstMoveIndex">Index of the first move run again: the stop point's, or its run-up's when it is a burn run's start.</param>
/// <param name="Trimmed">The first move cut to start at the resume X (a burn run cut off midway), or null.</param>
/// <param name="RowStartIndex">Index of the first move of the stop point's row (or of the first row after it).</param>
/// <param name="MoveCount">The plan's number of moves.</param>
/// <param name="RunsBefore">Burn runs before <paramref name="FirstMoveIndex"/>.</param>
/// <param name="RowsBefore">Rows finished before it.</param>
/// <param name="LastRowBefore">The row of the last move before it (-1: none).</param>
public sealed record RasterResume(RunStopPoint Stop, long FirstMoveIndex, Move? Trimmed, long RowStartIndex, long MoveCount, long RunsBefore, int RowsBefore, int LastRowBefore)
{
    /// <summary>Whether nothing is left to run.</summary>
    public bool Done => FirstMoveIndex == MoveCount;
}

namespace LaserEngrave.Core.Planning;

/// <summary>One visited image row of a plan: where its moves sit in the whole sequence (for progress and resume).</summary>
/// <param name="Row">Image row index.</param>
/// <param name="LeftToRight">Direction in which the row burns.</param>
/// <param name="FirstMoveIndex">Index in <see cref="RasterPlan.Moves()"/> of the row's first move (the travel into it, when there is one).</param>
/// <param name="MoveCount">Number of moves tagged with this row.</param>
public readonly record struct PlanRow(int Row, bool LeftToRight, long FirstMoveIndex, int MoveCount);

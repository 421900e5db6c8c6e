using System.Runtime.CompilerServices;

namespace LaserEngrave.Core.Planning;

/// <summary>
/// A stroke of a timed raster program: one X Move Absolute from rest at <see cref="StartX"/> to rest at <see cref="EndX"/>
/// at the burn speed over a row's run-up, burn runs, flown gaps and run-out, the laser switched on and off by time at
/// each run's edges (docs/execution.md).
/// </summary>
/// <remarks>
/// The start is the run-up's: a run-up before the first edge within the travel, also when the plan's first move of the
/// stroke is shorter (a run resumed midway). Offsets are microsteps from the start; times seconds from the stroke's
/// Move Absolute arriving (<see cref="Plan"/>).
/// </remarks>
public sealed class StrokeStep
{
    private Move[] _moves = new Move[16];
    private int[] _runs = new int[8];
    private (long Exit, long Entry)[] _gaps = new (long, long)[8];
    private int _runCount;
    private StrokePlan? _reused;

    internal StrokeStep()
    {
    }

    /// <summary>Absolute X where the stroke starts, microsteps (the stage is brought there at rest).</summary>
    public long StartX { get; private set; }

    /// <summary>Absolute X where it ends, microsteps: its Move Absolute's target.</summary>
    public long EndX { get; private set; }

    /// <summary>The row's Y, microsteps.</summary>
    public long Y { get; private set; }

    /// <summary>+1 towards +X, -1 towards -X.</summary>
    public int Direction => Math.Sign(EndX - StartX);

    /// <summary>Length from start to end, microsteps.</summary>
    public long Length => Math.Abs(EndX - StartX);

    /// <summary>Index in the plan's moves of the stroke's first move.</summary>
    public long FirstMoveIndex { get; private set; }

    /// <summary>How many of the plan's moves the stroke runs.</summary>
    public int MoveCount { get; private set; }

    /// <summary>How many burn runs it has.</summary>
    public int RunCount => _runCount;

    /// <summary>The gaps between its runs as offsets (the exit of one run, the entry of the next), in order.</summary>
    public ReadOnlySpan<(long Exit, long Entry)> Gaps => _gaps.AsSpan(0, Math.Max(0, _runCount - 1));

    /// <summary>Its motion and flown gaps.</summary>
    public StrokePlan Plan { get; private set; } = null!;

    /// <summary>When the first run's switch-on edge is crossed, s from the stroke's start (0 without a run).</summary>
    public double FirstEdgeSeconds { get; private set; }

    /// <summary>When the last run's switch-off edge is crossed, s from the stroke's start (0 without a run).</summary>
    public double LastOffSeconds { get; private set; }

    /// <summary>The plan's moves the stroke runs, in order.</summary>
    public ReadOnlySpan<Move> Moves => _moves.AsSpan(0, MoveCount);

    /// <summary>The plan's <paramref name="i"/>-th move of the stroke.</summary>
    public Move MoveAt(int i) => (uint)i < (uint)MoveCount ? _moves[i] : throw new ArgumentOutOfRangeException(nameof(i));

    /// <summary>The <paramref name="k"/>-th burn run.</summary>
    public BurnRun RunAt(int k) =>
        (uint)k < (uint)_runCount ? new BurnRun(_moves[_runs[k]], FirstMoveIndex + _runs[k]) : throw new ArgumentOutOfRangeException(nameof(k));

    /// <summary>Offset of absolute <paramref name="x"/> from the start, microsteps.</summary>
    public long Distance(long x) => Math.Abs(x - StartX);

    /// <summary>When the stage crosses absolute <paramref name="x"/> (an edge), s from the stroke's start.</summary>
    public double TimeAt(long x) => Plan.TimeAt(Distance(x));

    /// <summary>Starts the next stroke in this one's buffers.</summary>
    internal void Begin(long firstMoveIndex)
    {
        FirstMoveIndex = firstMoveIndex;
        MoveCount = 0;
        _runCount = 0;
    }

    [MethodImpl(MethodImplOptions.AggressiveInlining)]
    internal void Add(in Move move)
    {
        if (MoveCount == _moves.Length)
        {
            Array.Resize(ref _moves, _moves.Length * 2);
        }

        if (move.Kind == MoveKind.Burn)
        {
            if (_runCount == _runs.Length)
            {
                Array.Resize(ref _runs, _runs.Length * 2);
            }

            _runs[_runCount++] = MoveCount;
        }

        _moves[MoveCount++] = move;
    }

    /// <summary>The last move added.</summary>
    internal ref readonly Move Last => ref _moves[MoveCount - 1];

    /// <summary>
    /// Settles the stroke: its start (a run-up of <paramref name="runUp"/> before the first edge, within the travel), its gaps
    /// and its plan under <paramref name="timing"/>; with <paramref name="reuse"/> planned into one plan kept for the next stroke.
    /// </summary>
    [MethodImpl(HotPath.Optimized)]
    internal void Close(TimedSwitching timing, long runUp, long travelX, bool reuse)
    {
        ref readonly var first = ref _moves[0];
        ref readonly var last = ref _moves[MoveCount - 1];
        var dir = Math.Sign(last.X1 - first.X0);
        var startX = first.X0;
        if (_runCount > 0)
        {
            var onX = _moves[_runs[0]].X0;
            if (Math.Abs(onX - first.X0) < runUp)
            {
                startX = Math.Clamp(onX - (dir * runUp), 0, travelX);
            }
        }

        StartX = startX;
        EndX = last.X1;
        Y = first.Y0;
        if (_gaps.Length < _runCount)
        {
            Array.Resize(ref _gaps, Math.Max(_runCount, _gaps.Length * 2));
        }

        for (var k = 1; k < _runCount; k++)
        {
            _gaps[k - 1] = (Distance(_moves[_runs[k - 1]].X1), Distance(_moves[_runs[k]].X0));
        }

        var length = Length;
        if (reuse)
        {
            _reused ??= new StrokePlan();
            _reused.Replan(timing, length, Gaps);
            Plan = _reused;
        }
        else
        {
            Plan = timing.Stroke(length, Gaps.ToArray());
        }

        FirstEdgeSeconds = _runCount > 0 ? TimeAt(_moves[_runs[0]].X0) : 0;
        LastOffSeconds = _runCount > 0 ? TimeAt(_moves[_runs[_runCount - 1]].X1) : 0;
    }
}

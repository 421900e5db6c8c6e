using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The run's accounting: the one count of moves, rows (strokes, dots) and burn runs done that the progress, the stop point
/// and the log all read, and the estimate of what is done and left. Safe to call from any thread; its lock is taken last
/// (under the engine's) and it calls nothing out.
/// </summary>
/// <remarks>
/// A row counts as done once a move of a later row completes (or the plan ends); a resumed run counts what was done
/// before its stop point first. The cut pixel of a timed run stopped mid-run is the timed strategy's (it needs the
/// stroke's motion), added to <see cref="StopPoint"/>'s answer by the engine.
/// </remarks>
internal sealed class RunAccounting(int rowsTotal, long runsTotal)
{
    private readonly Lock _lock = new();

    // The move being executed (the first not completed), the row it is in, and the move on the stage.
    private long _moveIndex;
    private int _moveRow;
    private Move? _currentMove;
    private long _currentIndex = -1;
    private int _rowsDone;
    private int _lastRow = -1;
    private long _runsDone;
    private double _estimateBefore;
    private double _estimateTotal;
    private double _estimatePreparation;
    private PlanEstimator? _estimator;

    public int RowsTotal { get; } = rowsTotal;

    public long RunsTotal { get; } = runsTotal;

    public int RowsDone
    {
        get
        {
            lock (_lock)
            {
                return _rowsDone;
            }
        }
    }

    public long RunsDone
    {
        get
        {
            lock (_lock)
            {
                return _runsDone;
            }
        }
    }

    /// <summary>The estimate of the whole plan's engraving, s (a resumed run's too: what was done before counts).</summary>
    public double EstimateTotal
    {
        get
        {
            lock (_lock)
            {
                return _estimateTotal;
            }
        }

        set
        {
            lock (_lock)
            {
                _estimateTotal = value;
            }
        }
    }

    /// <summary>The estimate of what was done before a resumed run's stop point, s (0 for a run from the start).</summary>
    public double EstimateBefore
    {
        get
        {
            lock (_lock)
            {
                return _estimateBefore;
            }
        }

        set
        {
            lock (_lock)
            {
                _estimateBefore = value;
            }
        }
    }

    /// <summary>The estimate of what preflight did and the travel to the first move take, s.</summary>
    public double EstimatePreparation
    {
        get
        {
            lock (_lock)
            {
                return _estimatePreparation;
            }
        }

        set
        {
            lock (_lock)
            {
                _estimatePreparation = value;
            }
        }
    }

    /// <summary>The estimate this run adds its completed moves to (a step-by-step run's progress reads it); null for the others.</summary>
    public PlanEstimator? Estimator
    {
        get
        {
            lock (_lock)
            {
                return _estimator;
            }
        }

        set
        {
            lock (_lock)
            {
                _estimator = value;
            }
        }
    }

    /// <summary>The stop point is at move <paramref name="index"/> (the first not done), in or before row <paramref name="row"/>.</summary>
    public void At(long index, int row)
    {
        lock (_lock)
        {
            _moveIndex = index;
            _moveRow = row;
        }
    }

    /// <summary>Move <paramref name="index"/> (of row <paramref name="row"/>) is being executed: the first not done, and the one on the stage.</summary>
    public void Executing(long index, int row, Move? move = null)
    {
        lock (_lock)
        {
            _moveIndex = index;
            _currentIndex = index;
            _moveRow = row;
            _currentMove = move;
        }
    }

    /// <summary>The move on the stage (a timed run's burn run or travel), ahead of the moves completed.</summary>
    public void Current(Move move, long index)
    {
        lock (_lock)
        {
            _currentMove = move;
            _currentIndex = index;
        }
    }

    /// <summary>Counts a move done before a resumed run's stop point (a dot as a burn of its row).</summary>
    public void CountDone(MoveKind kind, int row)
    {
        lock (_lock)
        {
            Count(kind, row);
        }
    }

    /// <summary>A resumed run: the rows (a drawing's strokes) and runs (its paths) done before its stop point, and the row of the last move before it (-1: none under way).</summary>
    public void DoneBefore(int rows, long runs, int lastRow = -1)
    {
        lock (_lock)
        {
            _rowsDone = rows;
            _runsDone = runs;
            _lastRow = lastRow;
        }
    }

    /// <summary>Move <paramref name="index"/> completed: counted, added to the estimate, and the stop point after it.</summary>
    public void Completed(Move move, long index)
    {
        lock (_lock)
        {
            _estimator?.Add(move);
            Count(move.Kind, move.Row);

            // The stop point: the first move not done, and a row it is in or after (timed runs complete moves in order,
            // behind the switchings, so the row of the last one done).
            _moveIndex = index + 1;
            _moveRow = move.Row;
        }
    }

    /// <summary>A drawing's stroke <paramref name="index"/> is done (a row), and with it its path when it was the path's last (a run).</summary>
    public void StrokeDone(int index, bool lastOfPath)
    {
        lock (_lock)
        {
            _rowsDone++;
            if (lastOfPath)
            {
                _runsDone++;
            }

            _moveIndex = index + 1;
        }
    }

    /// <summary>The plan has run to its end: the last row counts as done, the stop point after every row.</summary>
    /// <param name="index">The index after the last move, or null when the last completion set it.</param>
    /// <param name="row">The row after the last (the image's height).</param>
    public void Ended(long? index, int row)
    {
        lock (_lock)
        {
            _moveIndex = index ?? _moveIndex;
            _moveRow = row;
            _currentMove = null;
            if (_lastRow >= 0)
            {
                _rowsDone++;
                _lastRow = -1;
            }
        }
    }

    /// <summary>The run has completed: the estimate of its moves is closed (the last move's end counted).</summary>
    public void Finish()
    {
        lock (_lock)
        {
            _estimator?.Finish();
        }
    }

    /// <summary>The first move not completed; a move whose stage stopped at its end counts as completed (only its reply was lost).</summary>
    /// <param name="stoppedAt">Where the stage stopped, when both axes said; null when it could not be asked.</param>
    public RunStopPoint StopPoint((long X, long Y)? stoppedAt)
    {
        lock (_lock)
        {
            var index = _moveIndex;
            if (stoppedAt is { } at && _currentMove is { } move && at.X == move.X1 && at.Y == move.Y1 && index == _currentIndex)
            {
                index++;
            }

            return new RunStopPoint(_moveRow, index, stoppedAt?.X, stoppedAt?.Y);
        }
    }

    /// <summary>A progress snapshot.</summary>
    /// <param name="elapsed">Time since the run started.</param>
    /// <param name="engravingSeconds">Time spent engraving (without pauses and positioning), or null before the engraving started.</param>
    /// <param name="byClock">Whether the run keeps to its estimate (timed runs and dots: the same timeline), so the clock says how much of it is done.</param>
    public RunProgress Snapshot(RunState state, TimeSpan elapsed, double? engravingSeconds, bool byClock, long x, long y, bool laserOn)
    {
        lock (_lock)
        {
            var estimateDone = engravingSeconds is not { } engraved ? 0
                : byClock ? Math.Min(_estimateTotal - _estimateBefore, engraved)
                : _estimator?.ElapsedSeconds ?? 0;
            var done = _estimateBefore + estimateDone;
            var percent = _estimateTotal > 0 ? Math.Clamp(100 * done / _estimateTotal, 0, 100) : 0;
            var engraving = engravingSeconds ?? 0;
            var ratio = estimateDone > 1 && engraving > 0 ? engraving / estimateDone : 1;
            var remaining = Math.Max(0, _estimateTotal - done) * ratio;
            return new RunProgress(state, _rowsDone, RowsTotal, _runsDone, RunsTotal, percent, elapsed, TimeSpan.FromSeconds(remaining), x, y, laserOn);
        }
    }

    private void Count(MoveKind kind, int row)
    {
        if (kind == MoveKind.Burn)
        {
            _runsDone++;
        }

        if (row != _lastRow)
        {
            _rowsDone += _lastRow >= 0 ? 1 : 0;
            _lastRow = row;
        }
    }
}

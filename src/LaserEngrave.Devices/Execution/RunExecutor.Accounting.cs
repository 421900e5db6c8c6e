using System.Globalization;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;
using LaserEngrave.Core.Vectors;
using LaserEngrave.Devices.Abstractions;
using LaserEngrave.Devices.Scheduling;
using LaserEngrave.Devices.Zaber;

namespace LaserEngrave.Devices.Execution;

/// <summary>Accounting: the one count of moves, rows (strokes, dots) and runs done that progress, the stop point and the log all read.</summary>
public sealed partial class RunExecutor
{
    private void Completed(Move move, long index)
    {
        RunProgress progress;
        lock (_lock)
        {
            _estimator?.Add(move);
            if (move.Kind == MoveKind.Burn)
            {
                _runsDone++;
            }

            if (move.Row != _lastRow)
            {
                _rowsDone += _lastRow >= 0 ? 1 : 0;
                _lastRow = move.Row;
            }

            // The stop point: the first move not done, and a row it is in or after (timed runs complete moves in order,
            // behind the switchings, so the row of the last one done).
            _moveIndex = index + 1;
            _moveRow = move.Row;
            _progress = Snapshot();
            progress = _progress;
        }

        MoveCompleted?.Invoke(this, new MoveCompletedEventArgs(move, index));
        ProgressChanged?.Invoke(this, progress);
    }

    /// <summary>The first move not completed; a move whose stage stopped at its end counts as completed (only its reply was lost).</summary>
    private RunStopPoint StopPoint()
    {
        lock (_lock)
        {
            var index = _moveIndex;
            var row = _moveRow;
            if (_stoppedAtKnownPosition && _currentMove is { } move && _x == move.X1 && _y == move.Y1 && index == _currentIndex)
            {
                index++;
            }

            return CutWithin(new RunStopPoint(row, index, _stoppedAtKnownPosition ? _x : null, _stoppedAtKnownPosition ? _y : null));
        }
    }

    private RunProgress Snapshot()
    {
        var elapsed = TimeProvider.GetElapsedTime(_startTimestamp);
        // Timed runs keep to their estimate (the same timeline), so the clock says how much of it is done.
        var estimateDone = !_engravingStarted ? 0
            : _timing is not null || Job?.Dots is not null ? Math.Min(_estimateTotal - _estimateBefore, (TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving).TotalSeconds)
            : _estimator?.ElapsedSeconds ?? 0;
        var done = _estimateBefore + estimateDone;
        var percent = _estimateTotal > 0 ? Math.Clamp(100 * done / _estimateTotal, 0, 100) : 0;
        var engraving = !_engravingStarted ? 0 : (TimeProvider.GetElapsedTime(_engravingStart) - _notEngraving).TotalSeconds;
        var ratio = estimateDone > 1 && engraving > 0 ? engraving / estimateDone : 1;
        var remaining = Math.Max(0, _estimateTotal - done) * ratio;
        return new RunProgress(_state, _rowsDone, _rowsTotal, _runsDone, _runsTotal, percent, elapsed, TimeSpan.FromSeconds(remaining), _x, _y, _laser.On);
    }
}

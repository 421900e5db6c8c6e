using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Motion;
using LaserEngrave.Core.Planning;

namespace LaserEngrave.App.ViewModels;

/// <summary>
/// Where the laser is drawn between two progress reports of an image job's run: the move in flight, from where the last
/// report put the stage towards that move's end, at the move's planned pace (a travel's ramps at the travel speed, a
/// burn or overscan at the burn speed). It reads only the plan and the app's clock, never the ports: a run owns them.
/// </summary>
/// <remarks>The engine reports when a move ends; without this the cross stood still for a whole row and then jumped.</remarks>
public sealed class LaserPace
{
    private readonly PreparedJob _job;
    private readonly TimeProvider _time;

    // The engine reports on its thread and the page's timer asks on another.
    private readonly Lock _lock = new();
    private readonly double _burnPerS;
    private readonly double _travelPerS;
    private readonly double _accelerationPerS2;
    private IEnumerator<Move>? _moves;
    private long _index = -1;
    private long _movesDone = -1;
    private int _pass;
    private (long X, long Y) _from;
    private Move? _next;
    private DateTimeOffset _reportedAt;

    public LaserPace(PreparedJob job, TimeProvider time)
    {
        ArgumentNullException.ThrowIfNull(job);
        ArgumentNullException.ThrowIfNull(time);
        _job = job;
        _time = time;

        // Speeds in X microsteps: the plan's moves run along X (burns) or both axes at once (travels, the longer one sets the time).
        var perMm = 1000 / job.Spec.Profile.X.MicrostepUm;
        _burnPerS = job.Spec.Process.BurnSpeedMmPerS * perMm;
        _travelPerS = job.Spec.Process.TravelSpeedMmPerS * perMm;
        _accelerationPerS2 = job.Spec.Process.AccelerationMmPerS2 * perMm;
    }

    /// <summary>A progress report: <paramref name="movesDone"/> of the pass's moves are done and the stage stood at (x, y).</summary>
    public void Report(int pass, long movesDone, long x, long y)
    {
        lock (_lock)
        {
            ReportLocked(pass, movesDone, x, y);
        }
    }

    /// <summary>The laser now: on the move in flight at its planned pace; where the last report put it when no move is in flight or the run is not moving; null before the first report.</summary>
    public (long X, long Y)? Now(bool moving)
    {
        lock (_lock)
        {
            return NowLocked(moving);
        }
    }

    private void ReportLocked(int pass, long movesDone, long x, long y)
    {
        if (pass == _pass && movesDone == _movesDone)
        {
            // The same move still in flight: its clock keeps running from when it began.
            return;
        }

        if (pass != _pass || movesDone <= _index)
        {
            // A new pass starts the plan again.
            _moves?.Dispose();
            _moves = null;
            _index = -1;
        }

        _pass = pass;
        _movesDone = movesDone;
        _from = (x, y);
        _reportedAt = _time.GetUtcNow();
        _next = MoveAt(movesDone);
    }

    private (long X, long Y)? NowLocked(bool moving)
    {
        if (_movesDone < 0)
        {
            return null;
        }

        if (!moving || _next is not { } move)
        {
            return _from;
        }

        var length = Math.Max(Math.Abs(move.X1 - _from.X), Math.Abs(move.Y1 - _from.Y));
        if (length == 0)
        {
            return _from;
        }

        var seconds = (_time.GetUtcNow() - _reportedAt).TotalSeconds;
        var covered = move.Kind == MoveKind.Travel
            ? new TrapezoidProfile(length, _travelPerS, _accelerationPerS2).DistanceAt(seconds)
            : Math.Min(length, seconds * _burnPerS);
        var share = covered / length;
        return (_from.X + (long)Math.Round((move.X1 - _from.X) * share), _from.Y + (long)Math.Round((move.Y1 - _from.Y) * share));
    }

    /// <summary>The plan's move at <paramref name="index"/> (from 0), walking the plan forward only; null past its end.</summary>
    private Move? MoveAt(long index)
    {
        _moves ??= _job.Plan.Moves().GetEnumerator();
        while (_index < index)
        {
            if (!_moves.MoveNext())
            {
                return null;
            }

            _index++;
        }

        return _moves.Current;
    }
}

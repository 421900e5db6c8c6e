namespace LaserEngrave.Simulator.Motion;

/// <summary>Where one axis was, is and will be: a time-ordered list of <see cref="MotionSegment"/>s.</summary>
/// <remarks>
/// The virtual device plans into it and reads its own position from it; the burn recorder reads the whole history.
/// A new plan replaces whatever was planned after its start (pre-emption). Thread-safe.
/// </remarks>
public sealed class AxisTrajectory
{
    private readonly Lock _lock = new();
    private readonly List<MotionSegment> _segments = [];

    public AxisTrajectory(double initialPosition, double startSeconds = 0)
    {
        _segments.Add(MotionSegment.Hold(startSeconds, initialPosition));
    }

    /// <summary>A copy of every segment so far, in time order.</summary>
    public IReadOnlyList<MotionSegment> Segments
    {
        get
        {
            lock (_lock)
            {
                return [.. _segments];
            }
        }
    }

    /// <summary>When the last planned motion ends (the axis rests from then on).</summary>
    public double EndSeconds
    {
        get
        {
            lock (_lock)
            {
                return _segments[^1].EndSeconds;
            }
        }
    }

    /// <summary>Drops what was planned after <paramref name="fromSeconds"/> and appends <paramref name="plan"/>.</summary>
    public void Replace(double fromSeconds, IEnumerable<MotionSegment> plan)
    {
        ArgumentNullException.ThrowIfNull(plan);
        lock (_lock)
        {
            // Keep the first segment even when the plan starts at the same instant: it anchors queries before it.
            while (_segments.Count > 1 && _segments[^1].StartSeconds >= fromSeconds)
            {
                _segments.RemoveAt(_segments.Count - 1);
            }

            var last = _segments[^1];
            if (last.EndSeconds > fromSeconds)
            {
                _segments[^1] = last with { DurationSeconds = Math.Max(0, fromSeconds - last.StartSeconds) };
            }

            foreach (var segment in plan)
            {
                if (segment.StartSeconds < _segments[^1].StartSeconds)
                {
                    throw new ArgumentException($"segment at {segment.StartSeconds} s starts before {_segments[^1].StartSeconds} s", nameof(plan));
                }

                _segments.Add(segment);
            }
        }
    }

    public double PositionAt(double seconds)
    {
        lock (_lock)
        {
            return _segments[IndexAt(seconds)].PositionAt(seconds);
        }
    }

    public double VelocityAt(double seconds)
    {
        lock (_lock)
        {
            return _segments[IndexAt(seconds)].VelocityAt(seconds);
        }
    }

    // The last segment that has started by `seconds` (the first one for earlier times). Caller holds _lock.
    private int IndexAt(double seconds)
    {
        int lo = 0, hi = _segments.Count - 1;
        while (lo < hi)
        {
            var mid = (lo + hi + 1) / 2;
            if (_segments[mid].StartSeconds <= seconds)
            {
                lo = mid;
            }
            else
            {
                hi = mid - 1;
            }
        }

        return lo;
    }
}

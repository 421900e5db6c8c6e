using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Serial;

/// <summary>
/// Work done one piece after the other, each at its time on the simulation's clock (virtual time only): a frame's or
/// line's action after its bytes, a reply's bytes onto the host's end.
/// </summary>
/// <remarks>
/// It does what a loop awaiting a channel, then a delay, did (LinkSession's action and write loops before issue 38):
/// the next piece's timer is set when the one before it has run, at the same instant and so to the same tick; a piece
/// added while none waits sets its timer at once. What is gone is the loop's wake-up, a step of the simulation's loop
/// for every message, and the delay's task, timer and registration allocated for each.
/// </remarks>
internal sealed class TimedSequence(SimulationClock clock)
{
    private readonly Queue<(double AtSeconds, Action Work)> _waiting = new();
    private ITimer? _timer;
    private bool _posted;
    private bool _stopped;

    /// <summary>Does <paramref name="work"/> at <paramref name="atSeconds"/>, after every piece added before it.</summary>
    public void Add(double atSeconds, Action work)
    {
        if (_stopped)
        {
            return;
        }

        _waiting.Enqueue((atSeconds, work));
        if (_timer is null && !_posted && _waiting.Count == 1)
        {
            // The loop this replaces woke in a step of its own: work already due still runs in a step of its own, never
            // in the middle of the code that added it.
            if (!clock.IsDue(atSeconds))
            {
                Next();
            }
            else
            {
                _posted = true;
                SynchronizationContext.Current!.Post(static s => ((TimedSequence)s!).Posted(), this);
            }
        }
    }

    /// <summary>Drops every piece not yet done; none is done after this.</summary>
    public void Stop()
    {
        _stopped = true;
        _waiting.Clear();
        _timer?.Dispose();
        _timer = null;
    }

    private void Posted()
    {
        _posted = false;
        Next();
    }

    // The head's time has come (to the tick: it is done without asking the clock again, as the loop's delay returned).
    private void Fire()
    {
        _timer?.Dispose();
        _timer = null;
        if (!_stopped && _waiting.TryDequeue(out var piece))
        {
            piece.Work();
            Next();
        }
    }

    // Does the pieces whose time has come, then sets the timer for the next; as the loop did, a piece is done at its
    // instant after the one before it, and the next one's wait starts from there.
    private void Next()
    {
        while (!_stopped && _waiting.TryPeek(out var piece))
        {
            if (!clock.IsDue(piece.AtSeconds))
            {
                _timer = clock.At(piece.AtSeconds, Fire);
                return;
            }

            _waiting.Dequeue();
            piece.Work();
        }
    }
}

using LaserEngrave.Core.Planning;

namespace LaserEngrave.Devices.Execution;

/// <summary>
/// The moves of a timed run waiting to be reported done, in plan order: a move is queued once its stroke has come that
/// far, and reported (<see cref="MoveCompletions(Action{Move, long})"/>'s callback) once every move before it is and, for
/// a burn run, its switch-on is acknowledged: a run counts as burned only when the gate said it came on.
/// </summary>
/// <remarks>Not thread-safe: the run's own thread queues and completes; the callback takes the engine's lock itself.</remarks>
internal sealed class MoveCompletions(Action<Move, long> completed)
{
    private readonly Queue<(Move Move, long Index, Task? Acknowledged)> _queue = new();
    private long _queuedUpTo = -1;

    /// <summary>Starts counting from <paramref name="firstIndex"/>: moves before it (a resumed run's) are never queued.</summary>
    public void StartAt(long firstIndex) => _queuedUpTo = firstIndex - 1;

    /// <summary>Queues a stroke's moves up to the plan's move <paramref name="index"/>, the last of them waiting for <paramref name="lastAcknowledged"/>; then reports what is done.</summary>
    public void UpTo(StrokeStep stroke, long index, Task? lastAcknowledged)
    {
        for (var i = 0; i < stroke.MoveCount && stroke.FirstMoveIndex + i <= index; i++)
        {
            Queue(stroke.MoveAt(i), stroke.FirstMoveIndex + i, index, lastAcknowledged);
        }

        Acknowledged();
    }

    /// <summary>Queues one move (a travel) waiting for <paramref name="acknowledged"/> (null: nothing); then reports what is done.</summary>
    public void Up(Move move, long index, Task? acknowledged)
    {
        Queue(move, index, index, acknowledged);
        Acknowledged();
    }

    /// <summary>Reports, in order, every queued move whose switch-on (if it has one) is acknowledged, up to the first that is not.</summary>
    public void Acknowledged()
    {
        while (_queue.TryPeek(out var next) && (next.Acknowledged is null || next.Acknowledged.IsCompletedSuccessfully))
        {
            _queue.Dequeue();
            completed(next.Move, next.Index);
        }
    }

    // A move is queued once, however often its stroke comes back to it; only the last one asked for waits for the acknowledgement.
    private void Queue(Move move, long moveIndex, long index, Task? lastAcknowledged)
    {
        if (moveIndex > _queuedUpTo)
        {
            _queue.Enqueue((move, moveIndex, moveIndex == index ? lastAcknowledged : null));
            _queuedUpTo = moveIndex;
        }
    }
}

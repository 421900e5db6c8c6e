using LaserEngrave.Core.Jobs;
namespace LaserEngrave.App.Services;

/// <summary>
/// What undo puts back: the open job's settings (image settings, size, position, process; null before one is open)
/// and the job of layers, each edit of either one step.
/// </summary>
public sealed record WorkbenchState(JobSettings? Job, IReadOnlyList<JobLayer> Layers)
{
    public bool Equals(WorkbenchState? other) => other is not null && Job == other.Job && Layers.SequenceEqual(other.Layers);

    public override int GetHashCode() => HashCode.Combine(Job, Layers.Count);
}

/// <summary>
/// Undo and redo: immutable snapshots, one per committed change. Opening another image or job file starts a new
/// history: undo never swaps the artwork.
/// </summary>
public sealed class EditHistory<T>(int capacity = 100)
    where T : class, IEquatable<T>
{
    private readonly LinkedList<T> _undo = new();
    private readonly Stack<T> _redo = new();

    /// <summary>The job's settings as last recorded; null before the first.</summary>
    public T? Current { get; private set; }

    public bool CanUndo => _undo.Count > 0;

    public bool CanRedo => _redo.Count > 0;

    /// <summary>Keeps <paramref name="settings"/> as the job's state after a change; a state equal to the current one is no change.</summary>
    public void Record(T settings)
    {
        ArgumentNullException.ThrowIfNull(settings);
        if (settings.Equals(Current))
        {
            return;
        }

        if (Current is not null)
        {
            _undo.AddLast(Current);
            if (_undo.Count > capacity)
            {
                _undo.RemoveFirst();
            }
        }

        Current = settings;
        _redo.Clear();
    }

    /// <summary>Steps back: the settings to put back, or null when there is nothing to undo.</summary>
    public T? Undo()
    {
        if (_undo.Last is not { } last)
        {
            return null;
        }

        _undo.RemoveLast();
        _redo.Push(Current!);
        Current = last.Value;
        return Current;
    }

    /// <summary>Steps forward again after <see cref="Undo"/>: the settings to put back, or null when there is nothing to redo.</summary>
    public T? Redo()
    {
        if (!_redo.TryPop(out var next))
        {
            return null;
        }

        _undo.AddLast(Current!);
        Current = next;
        return Current;
    }

    /// <summary>Starts a new history at <paramref name="settings"/> (another image opened).</summary>
    public void Reset(T? settings)
    {
        _undo.Clear();
        _redo.Clear();
        Current = settings;
    }
}

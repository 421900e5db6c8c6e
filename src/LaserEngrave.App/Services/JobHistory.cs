using LaserEngrave.Core.Jobs;
namespace LaserEngrave.App.Services;

/// <summary>
/// The job's undo and redo: immutable snapshots of its settings (image settings, size, position, process), one per
/// committed change. Opening another image starts a new history: undo never swaps the artwork.
/// </summary>
public sealed class JobHistory(int capacity = 100)
{
    private readonly LinkedList<JobSettings> _undo = new();
    private readonly Stack<JobSettings> _redo = new();

    /// <summary>The job's settings as last recorded; null before the first.</summary>
    public JobSettings? Current { get; private set; }

    public bool CanUndo => _undo.Count > 0;

    public bool CanRedo => _redo.Count > 0;

    /// <summary>Keeps <paramref name="settings"/> as the job's state after a change; a state equal to the current one is no change.</summary>
    public void Record(JobSettings settings)
    {
        ArgumentNullException.ThrowIfNull(settings);
        if (settings == Current)
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
    public JobSettings? Undo()
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
    public JobSettings? Redo()
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
    public void Reset(JobSettings? settings)
    {
        _undo.Clear();
        _redo.Clear();
        Current = settings;
    }
}

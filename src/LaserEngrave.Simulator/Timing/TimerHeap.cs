namespace LaserEngrave.Simulator.Timing;

/// <summary>
/// The <see cref="SimulationLoop"/>'s timers by due time, then by the order they were set: a binary heap in which each
/// timer knows its place, so that a timer changed or cancelled is moved or taken out at once.
/// </summary>
/// <remarks>
/// A heap of entries (System.Collections.Generic.PriorityQueue) cannot take an entry out: a cancelled timer stayed in
/// it as a dead entry until it reached the top, and every reply watcher that was answered in time left one (issue 38).
/// The order is the same as that queue's: due time, then the sequence number the loop gives each setting.
/// Not thread-safe: the loop calls it under its lock.
/// </remarks>
internal sealed class TimerHeap
{
    private LoopTimer[] _items = new LoopTimer[64];
    private int _count;

    /// <summary>Timers waiting to fire.</summary>
    public int Count => _count;

    /// <summary>The timer due first, or null.</summary>
    public LoopTimer? Peek() => _count > 0 ? _items[0] : null;

    /// <summary>Puts <paramref name="timer"/> at <paramref name="due"/> (after every timer due then that was set before), or moves it there.</summary>
    public void Schedule(LoopTimer timer, long due, long sequence)
    {
        timer.Due = due;
        timer.Sequence = sequence;
        if (timer.HeapIndex < 0)
        {
            if (_count == _items.Length)
            {
                Array.Resize(ref _items, _count * 2);
            }

            Place(timer, _count++);
            Up(timer.HeapIndex);
        }
        else if (!Up(timer.HeapIndex))
        {
            Down(timer.HeapIndex);
        }
    }

    /// <summary>Takes <paramref name="timer"/> out; nothing when it is not in the heap.</summary>
    public void Remove(LoopTimer timer)
    {
        var index = timer.HeapIndex;
        if (index < 0)
        {
            return;
        }

        timer.HeapIndex = -1;
        var last = _items[--_count];
        _items[_count] = null!;
        if (index < _count)
        {
            Place(last, index);
            if (!Up(index))
            {
                Down(index);
            }
        }
    }

    private static bool Before(LoopTimer a, LoopTimer b) => a.Due < b.Due || (a.Due == b.Due && a.Sequence < b.Sequence);

    private void Place(LoopTimer timer, int index)
    {
        _items[index] = timer;
        timer.HeapIndex = index;
    }

    // Whether it moved.
    private bool Up(int index)
    {
        var timer = _items[index];
        var start = index;
        while (index > 0)
        {
            var parent = (index - 1) / 2;
            if (!Before(timer, _items[parent]))
            {
                break;
            }

            Place(_items[parent], index);
            index = parent;
        }

        Place(timer, index);
        return index != start;
    }

    private void Down(int index)
    {
        var timer = _items[index];
        while (true)
        {
            var child = (2 * index) + 1;
            if (child >= _count)
            {
                break;
            }

            if (child + 1 < _count && Before(_items[child + 1], _items[child]))
            {
                child++;
            }

            if (!Before(_items[child], timer))
            {
                break;
            }

            Place(_items[child], index);
            index = child;
        }

        Place(timer, index);
    }
}

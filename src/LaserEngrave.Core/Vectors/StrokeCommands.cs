using System.Collections;

namespace LaserEngrave.Core.Vectors;

/// <summary>
/// A stroke's axis commands in 8 bytes each instead of 24: every command is at one of its axis' updates on the time grid
/// all strokes share (or is the one position query), so it keeps the update's number and looks the time up in the
/// <see cref="UpdateGrid"/>: the same double, bit for bit, as the planner computed. A drawing of 500 000 strokes of
/// some 20 commands each holds 80 MB of commands instead of 240 MB.
/// </summary>
internal sealed class StrokeCommands : IReadOnlyList<AxisCommand>
{
    private readonly long[] _packed;
    private readonly UpdateGrid _grid;

    public StrokeCommands(AxisCommand[] commands, UpdateGrid grid)
    {
        _grid = grid;
        _packed = new long[commands.Length];
        for (var i = 0; i < commands.Length; i++)
        {
            var c = commands[i];
            var update = c.Kind == AxisCommandKind.Query ? 0 : grid.IndexOf(c.Axis, c.AtSeconds);
            _packed[i] = ((long)c.SpeedData << 32) | ((long)update << 3) | ((long)c.Kind << 1) | (long)c.Axis;
        }
    }

    public int Count => _packed.Length;

    public AxisCommand this[int index]
    {
        get
        {
            var p = _packed[index];
            var axis = (VectorAxis)(p & 1);
            var kind = (AxisCommandKind)((p >> 1) & 3);
            var update = (int)((p >> 3) & 0x1FFF_FFFF);
            var at = kind == AxisCommandKind.Query ? _grid.QuerySeconds : _grid.Time(axis, update);
            return new AxisCommand(at, axis, kind, (int)(p >> 32));
        }
    }

    public IEnumerator<AxisCommand> GetEnumerator()
    {
        for (var i = 0; i < _packed.Length; i++)
        {
            yield return this[i];
        }
    }

    IEnumerator IEnumerable.GetEnumerator() => GetEnumerator();
}

/// <summary>
/// The times of the axes' updates within a stroke: X at slots 0, 3, 5, 7, ..., Y at 1, 4, 6, 8, ... (slot 2 carries the
/// position query), each the one before plus its step, as the planner adds them up.
/// </summary>
internal sealed class UpdateGrid(double slot)
{
    private readonly List<double> _x = [0];
    private readonly List<double> _y = [slot];

    /// <summary>When the position query arrives: slot 2.</summary>
    public double QuerySeconds => 2 * slot;

    /// <summary>The time of <paramref name="axis"/>' update number <paramref name="update"/> (0 is its first).</summary>
    public double Time(VectorAxis axis, int update)
    {
        var times = axis == VectorAxis.X ? _x : _y;
        while (times.Count <= update)
        {
            var last = times[^1];
            times.Add(last + (last < 2 * slot ? 3 * slot : 2 * slot));
        }

        return times[update];
    }

    /// <summary>The number of the update at exactly <paramref name="seconds"/>.</summary>
    public int IndexOf(VectorAxis axis, double seconds)
    {
        var times = axis == VectorAxis.X ? _x : _y;
        var found = times.BinarySearch(seconds);
        while (found < 0 && seconds > times[^1])
        {
            Time(axis, times.Count);
            found = times.BinarySearch(seconds);
        }

        return found >= 0 ? found : throw new InvalidOperationException($"a command at {seconds} s is not on the {axis} axis' update grid");
    }
}

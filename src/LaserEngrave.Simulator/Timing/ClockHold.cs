namespace LaserEngrave.Simulator.Timing;

/// <summary>A hold on a <see cref="VirtualTimeProvider"/>; disposing it lets time move again (the default value holds nothing).</summary>
public readonly struct ClockHold : IDisposable, IEquatable<ClockHold>
{
    private readonly VirtualTimeProvider? _owner;
    private readonly long _id;

    internal ClockHold(VirtualTimeProvider owner, long id)
    {
        _owner = owner;
        _id = id;
    }

    public static bool operator ==(ClockHold left, ClockHold right) => left.Equals(right);

    public static bool operator !=(ClockHold left, ClockHold right) => !left.Equals(right);

    public void Dispose() => _owner?.Release(_id);

    public bool Equals(ClockHold other) => ReferenceEquals(_owner, other._owner) && _id == other._id;

    public override bool Equals(object? obj) => obj is ClockHold other && Equals(other);

    public override int GetHashCode() => HashCode.Combine(_owner, _id);
}

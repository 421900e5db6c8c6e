namespace LaserEngrave.Wire.Serial;

/// <summary>Cuts the bytes a link delivers into messages (Zaber frames, text lines).</summary>
/// <remarks>Called only by the reader loop of one <see cref="SerialChannel{TMessage}"/>, in the order the bytes came.</remarks>
/// <typeparam name="TMessage">What one message is.</typeparam>
public interface ISerialFramer<TMessage>
{
    /// <summary>Takes bytes that arrived together and hands each message they complete to <paramref name="deliver"/>, in order.</summary>
    /// <param name="bytes">The bytes.</param>
    /// <param name="arrivalTimestamp">When they arrived, on the channel's clock (not when the reader got to them).</param>
    /// <param name="deliver">Takes one message; called before the framer looks at the next byte.</param>
    void Push(ReadOnlySpan<byte> bytes, long arrivalTimestamp, Action<TMessage> deliver);

    /// <summary>Takes bytes one read returned, with what the link knows of their arrival (exact, or bounded: <see cref="StampedRead.EarliestArrival"/>).</summary>
    /// <param name="bytes">The bytes.</param>
    /// <param name="read">The read, its stamps on the channel's clock.</param>
    /// <param name="deliver">Takes one message.</param>
    void Push(ReadOnlySpan<byte> bytes, StampedRead read, Action<TMessage> deliver) => Push(bytes, read.ArrivalTimestamp, deliver);
}

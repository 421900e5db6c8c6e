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
}

using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Devices.Zaber;

/// <summary>A reply nobody asked for: Move Tracking, Limit Active, Manual Move Tracking, or an error with no request.</summary>
public sealed class ZaberReplyEventArgs(ZaberFrame reply) : EventArgs
{
    public ZaberFrame Reply { get; } = reply;
}

using LaserEngrave.Simulator.Timing;

namespace LaserEngrave.Simulator.Serial;

/// <summary>The delays of one link besides the wire: the USB-serial adapter each way and the device's processing, drawn from one seeded source.</summary>
internal sealed class LinkLatency(Jitter adapter, Jitter processing, Random random)
{
    /// <summary>The adapter's latency for one write of the host.</summary>
    public double ToDeviceSeconds() => adapter.SampleSeconds(random);

    /// <summary>The adapter's latency for one reply of the device.</summary>
    public double ToHostSeconds() => adapter.SampleSeconds(random);

    /// <summary>From a command's last byte to its effect (and its reply).</summary>
    public double ProcessingSeconds() => processing.SampleSeconds(random);
}

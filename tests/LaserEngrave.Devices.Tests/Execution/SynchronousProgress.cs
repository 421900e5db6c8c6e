using LaserEngrave.Devices.Execution;

namespace LaserEngrave.Devices.Tests.Execution;

/// <summary>Hands each session report on at once, on the run's thread (Progress&lt;T&gt; would post it elsewhere, later).</summary>
internal sealed class SynchronousProgress(Action<EngraveProgress> report) : IProgress<EngraveProgress>
{
    public void Report(EngraveProgress value) => report(value);
}

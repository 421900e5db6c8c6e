using System.Diagnostics;
using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Devices.Tests.Serial;

/// <summary>What a real port's reader can prove about when bytes arrived: quiet proofs from waits that timed out.</summary>
public class ArrivalProofTests
{
    private static long Ms(double ms) => (long)(ms * Stopwatch.Frequency / 1000);

    [Fact]
    public void PollTimeoutMs_JustAfterARead_WaitsInShortSteps()
    {
        Assert.Equal(ArrivalProof.StepMs, ArrivalProof.PollTimeoutMs(Ms(1000), Ms(1005), 100));
    }

    [Fact]
    public void PollTimeoutMs_LongAfterAReadOrBeforeAny_WaitsTheIdleTime()
    {
        Assert.Equal(100, ArrivalProof.PollTimeoutMs(Ms(1000), Ms(1000 + ArrivalProof.WindowMs + 1), 100));
        Assert.Equal(100, ArrivalProof.PollTimeoutMs(long.MinValue, Ms(1000), 100));
    }

    [Fact]
    public void QuietAfterTimeout_WaitTimedOut_ProvesQuietAtItsEnd()
    {
        Assert.Equal(Ms(1002), ArrivalProof.QuietAfterTimeout(long.MinValue, Ms(1000), 2));
        Assert.Equal(Ms(1010), ArrivalProof.QuietAfterTimeout(Ms(1010), Ms(1000), 2));
    }

    [Fact]
    public void Earliest_NoQuietProofSinceTheReadBefore_IsThatRead()
    {
        // A reader 30 ms late finds piece two waiting: nothing proves it came later than piece one's read.
        Assert.Equal(Ms(1000), ArrivalProof.Earliest(long.MinValue, Ms(1000), Ms(1030)));
    }

    [Fact]
    public void Earliest_QuietProven_IsTheProof()
    {
        Assert.Equal(Ms(1012), ArrivalProof.Earliest(Ms(1012), Ms(1000), Ms(1014)));
    }

    [Fact]
    public void Earliest_FirstRead_IsItsOwnStamp()
    {
        Assert.Equal(Ms(1000), ArrivalProof.Earliest(long.MinValue, long.MinValue, Ms(1000)));
    }
}

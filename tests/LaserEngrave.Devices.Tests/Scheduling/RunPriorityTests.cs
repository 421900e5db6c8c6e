using System.Runtime.InteropServices;
using LaserEngrave.Devices.Scheduling;

namespace LaserEngrave.Devices.Tests.Scheduling;

/// <summary>A run on real ports asks for a higher CPU priority and gives it back; on Linux nice is per thread, so every thread is reniced.</summary>
public class RunPriorityTests
{
    [Fact]
    public void Raise_OnLinux_RenicesThisThreadAndThreadsStartedLater_AndDisposePutsThemBack()
    {
        Assert.True(OperatingSystem.IsLinux(), "the per-thread nice values are Linux's; CI runs there");
        var before = Nice(ThreadId());
        int during;
        int startedDuring = int.MinValue;
        string description;
        using (var priority = RunPriority.Raise())
        {
            description = priority.Description;
            during = Nice(ThreadId());
            var thread = new Thread(() => startedDuring = Nice(ThreadId()));
            thread.Start();
            thread.Join();
        }

        var after = Nice(ThreadId());
        if (description.StartsWith("raised (nice -10 on every thread)", StringComparison.Ordinal))
        {
            Assert.Equal((RunPriority.RaisedNice, RunPriority.RaisedNice), (during, startedDuring));
            Assert.Equal(before, after);
        }
        else
        {
            // Not permitted here (no root, no CAP_SYS_NICE), or already raised by whoever started the tests: nothing changed.
            Assert.Matches("^(normal \\(raising it was not permitted|raised \\(nice -10 or less, as started)", description);
            Assert.Equal((before, before, before), (during, startedDuring, after));
        }
    }

    [Fact]
    public void Dispose_Twice_RestoresOnce()
    {
        var before = Nice(ThreadId());
        var priority = RunPriority.Raise();
        priority.Dispose();
        var lowered = RunPriority.Raise();
        priority.Dispose(); // must not put back what the second one raised
        var during = Nice(ThreadId());
        lowered.Dispose();

        Assert.Equal(lowered.Description.StartsWith("raised (nice -10 on", StringComparison.Ordinal) ? RunPriority.RaisedNice : before, during);
        Assert.Equal(before, Nice(ThreadId()));
    }

    private static int ThreadId() => int.Parse(Path.GetFileName(new DirectoryInfo("/proc/thread-self").LinkTarget!), System.Globalization.CultureInfo.InvariantCulture);

    private static int Nice(int tid) => getpriority(0, tid);

    [DllImport("libc", SetLastError = true)]
    [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
    private static extern int getpriority(int which, int who);
}

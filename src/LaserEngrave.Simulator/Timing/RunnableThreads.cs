using System.Collections.Concurrent;
using System.Globalization;

namespace LaserEngrave.Simulator.Timing;

/// <summary>Whether any other thread of this process is running or waiting for a CPU (Linux: /proc/self/task/*/stat).</summary>
/// <remarks>
/// The virtual clock may only jump when the code it simulates for has nothing left to do. Queued work items and holds
/// cover most of that, but not a thread that has been handed a reply and is then descheduled on a loaded machine before
/// it sends the next command or arms its next timer: to the clock that looks quiet, and it would jump past a step the
/// host has not taken yet (a spurious timeout, a watchdog trip, a dwell). The kernel knows better: such a thread is in
/// state R. No .NET API exposes per-thread run state, hence /proc. Elsewhere this reports false and the clock relies on
/// its other signs of activity only.
/// </remarks>
internal static class RunnableThreads
{
    private static readonly bool Supported = OperatingSystem.IsLinux() && Directory.Exists("/proc/self/task");

    // The clocks' own advancer threads, which are running while they look: never counted.
    private static readonly ConcurrentDictionary<int, byte> Ignored = new();

    /// <summary>Marks the calling thread as one never to count (call it on the thread itself).</summary>
    public static void IgnoreCurrentThread()
    {
        if (CurrentThreadId() is { } id)
        {
            Ignored[id] = 0;
        }
    }

    /// <summary>Forgets the calling thread.</summary>
    public static void ForgetCurrentThread()
    {
        if (CurrentThreadId() is { } id)
        {
            Ignored.TryRemove(id, out _);
        }
    }

    /// <summary>True when a thread of this process other than the ignored ones is running or runnable.</summary>
    public static bool AnyOtherRunnable()
    {
        if (!Supported)
        {
            return false;
        }

        try
        {
            foreach (var task in Directory.EnumerateDirectories("/proc/self/task"))
            {
                if (!int.TryParse(Path.GetFileName(task), NumberStyles.None, CultureInfo.InvariantCulture, out var id) || Ignored.ContainsKey(id))
                {
                    continue;
                }

                if (StateOf(task) == 'R')
                {
                    return true;
                }
            }
        }
        catch (IOException)
        {
            // A thread that ended while we looked; the next look decides.
            return true;
        }
        catch (UnauthorizedAccessException)
        {
            return false;
        }

        return false;
    }

    private static char StateOf(string task)
    {
        string stat;
        try
        {
            stat = File.ReadAllText(Path.Combine(task, "stat"));
        }
        catch (IOException)
        {
            return '?';
        }

        // "tid (comm) S ...": the name may hold spaces and parentheses, so the state follows the last ')'.
        var close = stat.LastIndexOf(')');
        return close >= 0 && close + 2 < stat.Length ? stat[close + 2] : '?';
    }

    private static int? CurrentThreadId()
    {
        if (!Supported)
        {
            return null;
        }

        try
        {
            var target = new FileInfo("/proc/thread-self").LinkTarget;
            return target is not null && int.TryParse(Path.GetFileName(target), NumberStyles.None, CultureInfo.InvariantCulture, out var id) ? id : null;
        }
        catch (IOException)
        {
            return null;
        }
    }
}

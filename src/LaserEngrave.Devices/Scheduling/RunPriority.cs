using System.ComponentModel;
using System.Diagnostics;
using System.Globalization;
using System.Runtime.InteropServices;

namespace LaserEngrave.Devices.Scheduling;

/// <summary>
/// Raises this process' CPU priority while a run drives real ports, and puts it back afterwards: timed laser switching
/// plans to the millisecond, and a computer busy with other work must not make the host send a switch-off late.
/// </summary>
/// <remarks>
/// Written by hand because .NET's own knobs do not reach the threads that matter on Linux: <c>Thread.Priority</c> does
/// nothing there (dotnet/runtime#91165), and <c>Process.PriorityClass</c> renices only the main thread, since Linux keeps
/// a nice value per thread. So on Linux every thread of the process is reniced, and threads started later (the thread
/// pool's) inherit it from the thread that starts them. On Windows the process' priority class is raised (High needs no
/// administrator); on macOS the process' nice value. Raising it needs the right to (root, CAP_SYS_NICE or RLIMIT_NICE
/// on Linux and macOS); without it the run goes on at the normal priority, and <see cref="Description"/> says so for
/// the log.
/// </remarks>
public sealed class RunPriority : IDisposable
{
    /// <summary>The nice value a run asks for on Linux and macOS (Windows: the High priority class).</summary>
    public const int RaisedNice = -10;

    private readonly List<(int Tid, int Nice)> _threads = [];
    private readonly ProcessPriorityClass? _windowsClass;
    private readonly int? _processNice;
    private int _disposed;

    private RunPriority(string description) => Description = description;

    private RunPriority(string description, List<(int, int)> threads)
        : this(description) => _threads = threads;

    private RunPriority(string description, ProcessPriorityClass windowsClass)
        : this(description) => _windowsClass = windowsClass;

    private RunPriority(string description, int processNice)
        : this(description) => _processNice = processNice;

    /// <summary>What the run had, for the log: "raised (...)" or "normal (...)" with the reason.</summary>
    public string Description { get; }

    /// <summary>Raises the priority if this computer allows it; never throws.</summary>
    public static RunPriority Raise()
    {
        try
        {
            if (OperatingSystem.IsWindows())
            {
                using var process = Process.GetCurrentProcess();
                var before = process.PriorityClass;
                if (before is ProcessPriorityClass.High or ProcessPriorityClass.RealTime)
                {
                    return new RunPriority($"raised (priority class {before}, as started)");
                }

                process.PriorityClass = ProcessPriorityClass.High;
                return new RunPriority("raised (priority class High)", before);
            }

            if (OperatingSystem.IsLinux())
            {
                return RaiseLinuxThreads();
            }

            if (OperatingSystem.IsMacOS())
            {
                var before = Native.GetNice(0);
                if (before <= RaisedNice)
                {
                    return new RunPriority(string.Create(CultureInfo.InvariantCulture, $"raised (nice {before}, as started)"));
                }

                return Native.SetNice(0, RaisedNice) == 0
                    ? new RunPriority(string.Create(CultureInfo.InvariantCulture, $"raised (nice {RaisedNice})"), before)
                    : new RunPriority("normal (raising it was not permitted; run as root to raise it)");
            }
        }
        catch (Exception e) when (e is Win32Exception or InvalidOperationException or UnauthorizedAccessException or IOException or DllNotFoundException or EntryPointNotFoundException)
        {
            return new RunPriority($"normal ({e.Message})");
        }

        return new RunPriority("normal (this system cannot raise it)");
    }

    private static RunPriority RaiseLinuxThreads()
    {
        var changed = new List<(int, int)>();
        var already = 0;
        foreach (var tid in ThreadIds())
        {
            Marshal.SetLastPInvokeError(0);
            var nice = Native.GetNice(tid);
            if (Marshal.GetLastPInvokeError() != 0)
            {
                continue; // The thread ended meanwhile.
            }

            if (nice <= RaisedNice)
            {
                already++;
                continue;
            }

            if (Native.SetNice(tid, RaisedNice) != 0)
            {
                if (Marshal.GetLastPInvokeError() is 1 or 13) // EPERM, EACCES
                {
                    Restore(changed);
                    return new RunPriority("normal (raising it was not permitted: needs root, CAP_SYS_NICE or an RLIMIT_NICE of 10 or more)");
                }

                continue; // ESRCH: the thread ended meanwhile.
            }

            changed.Add((tid, nice));
        }

        return changed.Count == 0 && already > 0
            ? new RunPriority(string.Create(CultureInfo.InvariantCulture, $"raised (nice {RaisedNice} or less, as started)"))
            : new RunPriority(string.Create(CultureInfo.InvariantCulture, $"raised (nice {RaisedNice} on every thread)"), changed);
    }

    // The process' thread ids (Linux keeps a nice value per thread), read only when a run on real ports starts and ends:
    // no clock is read, and the twin never comes here (EngraveSession skips it on the simulator).
    private static IEnumerable<int> ThreadIds()
    {
        foreach (var dir in Directory.EnumerateDirectories("/proc/self/task"))
        {
            if (int.TryParse(Path.GetFileName(dir), NumberStyles.None, CultureInfo.InvariantCulture, out var tid))
            {
                yield return tid;
            }
        }
    }

    private static void Restore(List<(int Tid, int Nice)> threads)
    {
        foreach (var (tid, nice) in threads)
        {
            _ = Native.SetNice(tid, nice);
        }

        // Threads started during the run inherited the raised value: put every thread still at it back to the normal one.
        if (threads.Count > 0)
        {
            var normal = threads.Max(t => t.Nice);
            foreach (var tid in ThreadIds())
            {
                if (Native.GetNice(tid) == RaisedNice)
                {
                    _ = Native.SetNice(tid, normal);
                }
            }
        }
    }

    /// <summary>Puts the priority back as it was before the run.</summary>
    public void Dispose()
    {
        if (Interlocked.Exchange(ref _disposed, 1) != 0)
        {
            return;
        }

        try
        {
            if (_windowsClass is { } windowsClass && OperatingSystem.IsWindows())
            {
                using var process = Process.GetCurrentProcess();
                process.PriorityClass = windowsClass;
            }
            else if (_processNice is { } nice)
            {
                _ = Native.SetNice(0, nice);
            }
            else
            {
                Restore(_threads);
            }
        }
        catch (Exception e) when (e is Win32Exception or InvalidOperationException or IOException)
        {
            // Lowering it back can only fail if the process is going away.
        }
    }

    private static class Native
    {
        private const int PrioProcess = 0;

        // On Linux, PRIO_PROCESS with a thread id addresses that one thread (setpriority(2), BUGS).
        public static int GetNice(int who) => getpriority(PrioProcess, who);

        public static int SetNice(int who, int nice) => setpriority(PrioProcess, who, nice);

        [DllImport("libc", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        private static extern int getpriority(int which, int who);

        [DllImport("libc", SetLastError = true)]
        [DefaultDllImportSearchPaths(DllImportSearchPath.SafeDirectories)]
        private static extern int setpriority(int which, int who, int prio);
    }
}

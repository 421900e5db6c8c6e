using System.ComponentModel;
using System.Diagnostics;
using System.Text;

namespace LaserEngrave.Devices.Tests.Fakes;

/// <summary>Two connected ptys made by socat (<see cref="A"/> and <see cref="B"/>, unique per instance); killed on dispose.</summary>
/// <remarks>socat is a hard requirement of the serial tests: when it is missing they fail with a message saying so.</remarks>
public sealed class SocatPair : IDisposable
{
    private readonly Process _socat;
    private readonly StringBuilder _log = new();
    private bool _transferring;

    public SocatPair()
    {
        var id = Guid.NewGuid().ToString("N")[..10];
        A = $"/tmp/le-{id}-a";
        B = $"/tmp/le-{id}-b";
        var start = new ProcessStartInfo("socat")
        {
            RedirectStandardError = true,
            RedirectStandardOutput = true,
            UseShellExecute = false,
        };
        foreach (var argument in new[] { "-d", "-d", $"pty,raw,echo=0,link={A}", $"pty,raw,echo=0,link={B}" })
        {
            start.ArgumentList.Add(argument);
        }

        try
        {
            _socat = Process.Start(start) ?? throw new InvalidOperationException("socat did not start");
        }
        catch (Win32Exception ex)
        {
            throw new InvalidOperationException(
                "socat is not installed, and the serial-port tests need it to make pty pairs: apt-get install socat (.ci/run does this)", ex);
        }

        _socat.ErrorDataReceived += (_, e) =>
        {
            lock (_log)
            {
                _log.AppendLine(e.Data);
                _transferring |= e.Data?.Contains("starting data transfer loop", StringComparison.Ordinal) == true;
            }
        };
        _socat.BeginErrorReadLine();

        var deadline = DateTime.UtcNow + TimeSpan.FromSeconds(10);
        while (!(File.Exists(A) && File.Exists(B) && Transferring))
        {
            if (_socat.HasExited || DateTime.UtcNow > deadline)
            {
                Dispose();
                throw new InvalidOperationException($"socat did not make the pty pair {A} / {B}:\n{Log}");
            }

            Thread.Sleep(5);
        }
    }

    /// <summary>Path of one end (a symlink to /dev/pts/N).</summary>
    public string A { get; }

    public string B { get; }

    public string Log
    {
        get
        {
            lock (_log)
            {
                return _log.ToString();
            }
        }
    }

    private bool Transferring
    {
        get
        {
            lock (_log)
            {
                return _transferring;
            }
        }
    }

    /// <summary>Kills socat: both ptys hang up, as when a USB adapter is pulled.</summary>
    public void Kill()
    {
        if (!_socat.HasExited)
        {
            _socat.Kill();
            _socat.WaitForExit(5000);
        }
    }

    public void Dispose()
    {
        Kill();
        _socat.Dispose();
        File.Delete(A);
        File.Delete(B);
    }
}

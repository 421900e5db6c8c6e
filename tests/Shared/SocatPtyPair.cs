using System.Diagnostics;

namespace LaserEngrave.Testing;

/// <summary>A virtual serial cable: two linked ptys made by socat, removed again on dispose.</summary>
/// <remarks>Compiled into each test project that needs it (tests/Shared), so the real serial path is tested everywhere the same way.</remarks>
internal sealed class SocatPtyPair : IAsyncDisposable
{
    private readonly Process _socat;

    private SocatPtyPair(Process socat, string a, string b)
    {
        _socat = socat;
        A = a;
        B = b;
    }

    public string A { get; }

    public string B { get; }

    /// <summary>Starts socat; fails (never skips) when socat is missing, since CI installs it.</summary>
    public static async Task<SocatPtyPair> StartAsync(CancellationToken cancellationToken)
    {
        var stem = $"/tmp/le-pty-{Guid.NewGuid():N}"[..20];
        var (a, b) = (stem + "-a", stem + "-b");
        var start = new ProcessStartInfo("socat")
        {
            ArgumentList = { "-d", "-d", $"pty,raw,echo=0,link={a}", $"pty,raw,echo=0,link={b}" },
            RedirectStandardError = true,
            RedirectStandardOutput = true,
            UseShellExecute = false,
        };
        Process socat;
        try
        {
            socat = Process.Start(start) ?? throw new InvalidOperationException("socat did not start");
        }
        catch (System.ComponentModel.Win32Exception ex)
        {
            throw new InvalidOperationException("socat is not installed; the pty tests need it (apt-get install socat; .ci/run installs it)", ex);
        }

        socat.ErrorDataReceived += (_, _) => { };
        socat.OutputDataReceived += (_, _) => { };
        socat.BeginErrorReadLine();
        socat.BeginOutputReadLine();
        var pair = new SocatPtyPair(socat, a, b);
        var waited = Stopwatch.StartNew();
        while (!(File.Exists(a) && File.Exists(b)))
        {
            if (socat.HasExited || waited.Elapsed > TimeSpan.FromSeconds(10))
            {
                await pair.DisposeAsync();
                throw new InvalidOperationException($"socat did not make {a} and {b}");
            }

            await Task.Delay(20, cancellationToken);
        }

        return pair;
    }

    /// <summary>Opens one end as a raw byte stream (socat made it raw, no echo).</summary>
    public static FileStream Open(string path) => new(path, FileMode.Open, FileAccess.ReadWrite, FileShare.ReadWrite, bufferSize: 0);

    public async ValueTask DisposeAsync()
    {
        if (!_socat.HasExited)
        {
            _socat.Kill(entireProcessTree: true);
            await _socat.WaitForExitAsync().WaitAsync(TimeSpan.FromSeconds(5));
        }

        _socat.Dispose();
        File.Delete(A);
        File.Delete(B);
    }
}

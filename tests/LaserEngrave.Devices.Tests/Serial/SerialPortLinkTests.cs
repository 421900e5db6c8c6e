using System.Diagnostics;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;

namespace LaserEngrave.Devices.Tests.Serial;

/// <summary><see cref="SerialPortLink"/> on socat pty pairs: the real System.IO.Ports path on Linux.</summary>
public class SerialPortLinkTests
{
    private static CancellationToken Token => TestContext.Current.CancellationToken;

    [Fact]
    public void Open_MissingPath_SaysNoSuchPort()
    {
        var path = $"/tmp/le-missing-{Guid.NewGuid():N}";

        var error = Assert.Throws<SerialPortException>(() => SerialPortLink.Open(path));

        Assert.Equal($"{path}: no such port", error.Message);
        Assert.Equal(path, error.PortName);
    }

    [Fact]
    public void Open_LinkLeftBehindBySocat_SaysNoSuchPort()
    {
        var path = $"/tmp/le-dangling-{Guid.NewGuid():N}";
        File.CreateSymbolicLink(path, "/dev/pts/le-gone");
        try
        {
            var error = Assert.Throws<SerialPortException>(() => SerialPortLink.Open(path));

            Assert.Equal($"{path}: no such port", error.Message);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Open_RegularFile_SaysNotASerialPort()
    {
        var path = Path.GetTempFileName();
        try
        {
            var error = Assert.Throws<SerialPortException>(() => SerialPortLink.Open(path));

            Assert.Equal($"{path}: not a serial port", error.Message);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task Open_SamePtyTwice_SecondSaysInUseByAnotherProgram()
    {
        using var pair = new SocatPair();
        await using var first = SerialPortLink.Open(pair.A);

        var error = Assert.Throws<SerialPortException>(() => SerialPortLink.Open(pair.A));

        Assert.Equal($"{pair.A}: port is in use by another program", error.Message);
    }

    [Fact]
    public async Task Open_SamePtyUnderAnotherName_SaysInUse()
    {
        using var pair = new SocatPair();
        var alias = $"/tmp/le-alias-{Guid.NewGuid():N}";
        File.CreateSymbolicLink(alias, pair.A);
        try
        {
            await using var first = SerialPortLink.Open(pair.A);

            var error = Assert.Throws<SerialPortException>(() => SerialPortLink.Open(alias));

            Assert.Equal($"{alias}: port is in use by another program", error.Message);
        }
        finally
        {
            File.Delete(alias);
        }
    }

    [Fact]
    public async Task Open_SecondOpenWhileTheFirstHoldsThePort_RefusedBeforeTheFirstsSettingsChange()
    {
        using var pair = new SocatPair();
        await using var first = SerialPortLink.Open(new SerialPortSettings(pair.A) { BaudRate = 9600 });

        // As root TIOCEXCL lets the second open through: the lock must refuse it before it configures the port.
        Assert.Throws<SerialPortException>(() => SerialPortLink.Open(new SerialPortSettings(pair.A) { BaudRate = 115200 }));

        Assert.Contains(" speed 9600 baud ", Stty(pair.A), StringComparison.Ordinal);
    }

    [Fact]
    public async Task Open_LockFileLinkPlantedInTemp_NotFollowedAndNoLockFileMade()
    {
        using var pair = new SocatPair();
        var device = File.ResolveLinkTarget(pair.A, returnFinalTarget: true)!.FullName;
        // Where earlier versions made their lock file, planted as a link to a file another user wants created.
        var planted = Path.Combine(Path.GetTempPath(), $"laserengrave-{device.Trim('/').Replace('/', '_')}.lock");
        var victim = Path.Combine(Path.GetTempPath(), $"le-victim-{Guid.NewGuid():N}");
        File.Delete(planted);
        File.CreateSymbolicLink(planted, victim);
        try
        {
            await using (SerialPortLink.Open(pair.A))
            {
                Assert.False(File.Exists(victim));
            }

            Assert.False(File.Exists(victim));
            Assert.DoesNotContain(Directory.GetFiles(Path.GetTempPath(), $"laserengrave-{device.Trim('/').Replace('/', '_')}*"), f => f != planted);
        }
        finally
        {
            File.Delete(planted);
            File.Delete(victim);
        }
    }

    [Fact]
    public async Task Open_AfterTheFirstLinkIsDisposed_OpensAgain()
    {
        using var pair = new SocatPair();
        await SerialPortLink.Open(pair.A).DisposeAsync();

        await using var again = SerialPortLink.Open(pair.A);

        Assert.Equal(pair.A, again.Name);
    }

    [Fact]
    public async Task WriteAsync_EveryByteValue_ArrivesUnchangedBothWays()
    {
        using var pair = new SocatPair();
        await using var a = SerialPortLink.Open(pair.A);
        await using var b = SerialPortLink.Open(pair.B);

        // Raw mode matters: 0x00, XON/XOFF, CR/LF, Ctrl-C and DEL must all pass untouched.
        var all = Enumerable.Range(0, 256).Select(i => (byte)i).ToArray();
        await a.WriteAsync(all, Token);
        Assert.Equal(all, await ReadExactlyAsync(b, all.Length));

        var reversed = all.Reverse().ToArray();
        await b.WriteAsync(reversed, Token);
        Assert.Equal(reversed, await ReadExactlyAsync(a, reversed.Length));
    }

    [Fact]
    public async Task ReadAsync_FewerBytesThanAsked_ReturnsWhatHasArrived()
    {
        using var pair = new SocatPair();
        await using var a = SerialPortLink.Open(pair.A);
        await using var b = SerialPortLink.Open(pair.B);
        var buffer = new byte[64];

        await a.WriteAsync(new byte[] { 7, 8, 9 }, Token);
        var n = await b.ReadAsync(buffer, Token).AsTask().Within();

        Assert.InRange(n, 1, 3);
        Assert.Equal(new byte[] { 7, 8, 9 }.Take(n), buffer.Take(n));
    }

    [Fact]
    public async Task Open_Settings_AreAppliedToTheTerminal()
    {
        using var pair = new SocatPair();
        var settings = new SerialPortSettings(pair.A)
        {
            BaudRate = 19200,
            DataBits = 7,
            Parity = SerialParity.Even,
            StopBits = SerialStopBits.Two,
            Handshake = SerialHandshake.RequestToSend,
        };
        await using (SerialPortLink.Open(settings))
        {
        }

        // socat keeps the pty alive, so stty reads what the port left in its termios. The Linux pty driver forces
        // CS8 and no parity whatever is asked, so data bits and parity can only be seen on a real UART.
        var stty = Stty(pair.A);

        Assert.Contains(" speed 19200 baud ", stty, StringComparison.Ordinal);
        foreach (var flag in new[] { "cstopb", "crtscts", "cread", "clocal", "-icanon", "-echo", "-isig", "-ixon", "-opost" })
        {
            Assert.Contains($" {flag} ", stty, StringComparison.Ordinal);
        }
    }

    [Fact]
    public async Task Open_XOnXOff_SetsSoftwareFlowControl()
    {
        using var pair = new SocatPair();
        await using (SerialPortLink.Open(new SerialPortSettings(pair.A) { Handshake = SerialHandshake.XOnXOff }))
        {
        }

        var stty = Stty(pair.A);

        Assert.Contains(" ixon ", stty, StringComparison.Ordinal);
        Assert.Contains(" ixoff ", stty, StringComparison.Ordinal);
        Assert.Contains(" -crtscts ", stty, StringComparison.Ordinal);
    }

    [Fact]
    public async Task Open_Defaults_Are9600With8N1AndNoHandshake()
    {
        using var pair = new SocatPair();
        await using (SerialPortLink.Open(new SerialPortSettings(pair.A) { BaudRate = 19200 }))
        {
        }

        await using (SerialPortLink.Open(pair.A))
        {
        }

        var stty = Stty(pair.A);

        Assert.Contains(" speed 9600 baud ", stty, StringComparison.Ordinal);
        foreach (var flag in new[] { "cs8", "-parenb", "-cstopb", "-crtscts", "-ixon", "-ixoff" })
        {
            Assert.Contains($" {flag} ", stty, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Open_ZeroBaudRate_NamesThePortAndTheValue()
    {
        var error = Assert.Throws<ArgumentException>(() => SerialPortLink.Open(new SerialPortSettings("/dev/ttyUSB0") { BaudRate = 0 }));

        Assert.StartsWith("/dev/ttyUSB0: baud rate must be above 0 (got 0)", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task DisposeAsync_WhileAReadIsPending_EndsTheReadWithZero()
    {
        using var pair = new SocatPair();
        var port = SerialPortLink.Open(pair.A);
        var read = port.ReadAsync(new byte[16], Token).AsTask();
        await Eventually.AssertStillPendingAsync(read);

        await port.DisposeAsync().AsTask().Within();

        Assert.Equal(0, await read.Within());
        Assert.Equal(0, await port.ReadAsync(new byte[16], Token).AsTask().Within());
    }

    [Fact]
    public async Task ReadAsync_Cancelled_EndsAtOnceAndTheNextReadStillGetsData()
    {
        using var pair = new SocatPair();
        await using var a = SerialPortLink.Open(pair.A);
        await using var b = SerialPortLink.Open(pair.B);
        using var cancel = CancellationTokenSource.CreateLinkedTokenSource(Token);
        var read = b.ReadAsync(new byte[16], cancel.Token).AsTask();
        await Eventually.AssertStillPendingAsync(read);

        await cancel.CancelAsync();

        await Assert.ThrowsAnyAsync<OperationCanceledException>(() => read.Within());
        await a.WriteAsync(new byte[] { 42 }, Token);
        Assert.Equal(new byte[] { 42 }, await ReadExactlyAsync(b, 1));
    }

    [Fact]
    public async Task ReadAsync_OtherEndHangsUp_ThrowsNamingThePortAndWritesFailAtOnce()
    {
        using var pair = new SocatPair();
        await using var port = SerialPortLink.Open(pair.A);
        var read = port.ReadAsync(new byte[16], Token).AsTask();
        await Eventually.AssertStillPendingAsync(read);

        pair.Kill();

        var error = await Assert.ThrowsAsync<IOException>(() => read.Within());
        Assert.Equal($"{pair.A}: the port was unplugged or its other end closed", error.Message);
        var write = await Assert.ThrowsAsync<IOException>(() => port.WriteAsync(new byte[] { 1 }, Token).AsTask().Within());
        Assert.Equal(error.Message, write.Message);
        await Assert.ThrowsAsync<IOException>(() => port.ReadAsync(new byte[16], Token).AsTask().Within());
        await port.DisposeAsync().AsTask().Within();
    }

    [Fact]
    public async Task WriteAsync_OtherEndHungUpWhileIdle_ThrowsNamingThePort()
    {
        using var pair = new SocatPair();
        await using var port = SerialPortLink.Open(pair.A);

        pair.Kill();

        var error = await Assert.ThrowsAsync<IOException>(() => port.WriteAsync(new byte[] { 1 }, Token).AsTask().Within());
        Assert.StartsWith($"{pair.A}: ", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task WriteAsync_AfterDispose_ThrowsNamingThePort()
    {
        using var pair = new SocatPair();
        var port = SerialPortLink.Open(pair.A);
        await port.DisposeAsync();

        var error = await Assert.ThrowsAsync<IOException>(() => port.WriteAsync(new byte[] { 1 }, Token).AsTask());

        Assert.Equal($"{pair.A}: the port is closed", error.Message);
    }

    private static async Task<byte[]> ReadExactlyAsync(SerialPortLink port, int count)
    {
        var data = new byte[count];
        var offset = 0;
        while (offset < count)
        {
            var n = await port.ReadAsync(data.AsMemory(offset), CancellationToken.None).AsTask().Within();
            Assert.NotEqual(0, n);
            offset += n;
        }

        return data;
    }

    /// <summary>`stty -a` of the pty as one line with spaces around every flag.</summary>
    private static string Stty(string path)
    {
        var start = new ProcessStartInfo("stty") { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var argument in new[] { "-F", path, "-a" })
        {
            start.ArgumentList.Add(argument);
        }

        using var process = Process.Start(start)!;
        var output = process.StandardOutput.ReadToEnd() + process.StandardError.ReadToEnd();
        process.WaitForExit();
        return $" {output.ReplaceLineEndings(" ").Replace(';', ' ')} ";
    }
}

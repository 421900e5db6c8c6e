using System.Diagnostics;
using LaserEngrave.Devices.Serial;
using LaserEngrave.Devices.Tests.Fakes;

namespace LaserEngrave.Devices.Tests.Serial;

public class NativeSerialPortTests
{
    private static CancellationToken Token => TestContext.Current.CancellationToken;

    [Fact]
    public void Open_MissingPath_SaysNoSuchPort()
    {
        var path = $"/tmp/le-missing-{Guid.NewGuid():N}";

        var error = Assert.Throws<SerialPortException>(() => NativeSerialPort.Open(path));

        Assert.Equal($"{path}: no such port", error.Message);
        Assert.Equal(path, error.PortName);
    }

    [Fact]
    public void Open_RegularFile_SaysNotASerialPort()
    {
        var path = Path.GetTempFileName();
        try
        {
            var error = Assert.Throws<SerialPortException>(() => NativeSerialPort.Open(path));

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
        await using var first = NativeSerialPort.Open(pair.A);

        var error = Assert.Throws<SerialPortException>(() => NativeSerialPort.Open(pair.A));

        Assert.Equal($"{pair.A}: port is in use by another program", error.Message);
    }

    [Fact]
    public async Task WriteAsync_EveryByteValue_ArrivesUnchangedBothWays()
    {
        using var pair = new SocatPair();
        await using var a = NativeSerialPort.Open(pair.A);
        await using var b = NativeSerialPort.Open(pair.B);

        // Raw mode matters: 0x00, XON/XOFF, CR/LF, Ctrl-C and DEL must all pass untouched.
        var all = Enumerable.Range(0, 256).Select(i => (byte)i).ToArray();
        await a.WriteAsync(all, Token);
        Assert.Equal(all, await ReadExactlyAsync(b, all.Length));

        var reversed = all.Reverse().ToArray();
        await b.WriteAsync(reversed, Token);
        Assert.Equal(reversed, await ReadExactlyAsync(a, reversed.Length));
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
        await using (NativeSerialPort.Open(settings))
        {
        }

        // socat keeps the pty alive, so stty reads what the port left in its termios. The Linux pty driver forces
        // CS8 and no parity whatever is asked, so data bits and parity can only be seen on a real UART.
        var stty = Run("stty", "-F", pair.A, "-a");

        Assert.Contains("speed 19200 baud", stty, StringComparison.Ordinal);
        foreach (var flag in new[] { "cstopb", "crtscts", "cread", "clocal", "-icanon", "-echo", "-isig", "-ixon", "-opost" })
        {
            Assert.Contains($" {flag} ", $" {stty.ReplaceLineEndings(" ").Replace(';', ' ')} ", StringComparison.Ordinal);
        }
    }

    [Fact]
    public async Task Open_Defaults_Are9600With8N1AndNoHandshake()
    {
        using var pair = new SocatPair();
        await using (NativeSerialPort.Open(pair.A))
        {
        }

        var stty = $" {Run("stty", "-F", pair.A, "-a").ReplaceLineEndings(" ").Replace(';', ' ')} ";

        Assert.Contains("speed 9600 baud", stty, StringComparison.Ordinal);
        foreach (var flag in new[] { "cs8", "-parenb", "-cstopb", "-crtscts", "-ixon", "-ixoff" })
        {
            Assert.Contains($" {flag} ", stty, StringComparison.Ordinal);
        }
    }

    [Fact]
    public void Open_UnsupportedBaudRate_NamesThePortAndTheRate()
    {
        using var pair = new SocatPair();

        var error = Assert.Throws<SerialPortException>(() => NativeSerialPort.Open(new SerialPortSettings(pair.A) { BaudRate = 12345 }));

        Assert.StartsWith($"{pair.A}: 12345 baud is not supported", error.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task DisposeAsync_WhileAReadIsPending_EndsTheReadWithZero()
    {
        using var pair = new SocatPair();
        var port = NativeSerialPort.Open(pair.A);
        var read = port.ReadAsync(new byte[16], Token).AsTask();
        await Task.Delay(50, Token);
        Assert.False(read.IsCompleted);

        await port.DisposeAsync().AsTask().Within();

        Assert.Equal(0, await read.Within());
    }

    [Fact]
    public async Task ReadAsync_OtherEndHangsUp_ThrowsNamingThePort()
    {
        using var pair = new SocatPair();
        await using var port = NativeSerialPort.Open(pair.A);
        var read = port.ReadAsync(new byte[16], Token).AsTask();

        pair.Kill();

        var error = await Assert.ThrowsAsync<IOException>(() => read.Within());
        Assert.StartsWith($"{pair.A}: ", error.Message, StringComparison.Ordinal);
        await Assert.ThrowsAsync<IOException>(() => port.WriteAsync(new byte[] { 1 }, Token).AsTask());
    }

    [Fact]
    public async Task WriteAsync_AfterDispose_ThrowsNamingThePort()
    {
        using var pair = new SocatPair();
        var port = NativeSerialPort.Open(pair.A);
        await port.DisposeAsync();

        var error = await Assert.ThrowsAsync<IOException>(() => port.WriteAsync(new byte[] { 1 }, Token).AsTask());

        Assert.Equal($"{pair.A}: the port is closed", error.Message);
    }

    private static async Task<byte[]> ReadExactlyAsync(NativeSerialPort port, int count)
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

    private static string Run(string program, params string[] arguments)
    {
        var start = new ProcessStartInfo(program) { RedirectStandardOutput = true, RedirectStandardError = true, UseShellExecute = false };
        foreach (var argument in arguments)
        {
            start.ArgumentList.Add(argument);
        }

        using var process = Process.Start(start)!;
        var output = process.StandardOutput.ReadToEnd() + process.StandardError.ReadToEnd();
        process.WaitForExit();
        return output;
    }
}

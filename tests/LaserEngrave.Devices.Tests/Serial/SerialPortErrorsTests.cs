using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Devices.Tests.Serial;

public class SerialPortErrorsTests
{
    [Theory]
    [InlineData(2, "/dev/ttyUSB3: no such port")]
    [InlineData(16, "/dev/ttyUSB3: port is in use by another program")]
    [InlineData(13, "/dev/ttyUSB3: permission denied (on Linux add the user to the dialout group)")]
    [InlineData(25, "/dev/ttyUSB3: not a serial port")]
    public void FromErrno_KnownErrors_OneLineNamingThePort(int errno, string message)
    {
        Assert.Equal(message, SerialPortErrors.FromErrno("/dev/ttyUSB3", errno).Message);
    }

    [Fact]
    public void FromErrno_OtherError_KeepsThePortAndTheSystemText()
    {
        var message = SerialPortErrors.FromErrno("/dev/ttyS0", 5).Message;

        Assert.StartsWith("/dev/ttyS0: cannot open: ", message, StringComparison.Ordinal);
        Assert.True(message.Length > "/dev/ttyS0: cannot open: ".Length);
    }

    [Fact]
    public void FromOpenFailure_AccessDeniedAroundEbusy_SaysInUse()
    {
        // What System.IO.Ports throws on Linux when another user's program holds the tty with TIOCEXCL.
        var error = new UnauthorizedAccessException("Access to the port '/dev/ttyUSB3' is denied.", new IOException("Device or resource busy", 16));

        var result = SerialPortErrors.FromOpenFailure("/dev/ttyUSB3", error);

        Assert.Equal("/dev/ttyUSB3: port is in use by another program", result.Message);
        Assert.Equal("/dev/ttyUSB3", result.PortName);
    }

    [Fact]
    public void FromOpenFailure_AccessDeniedAroundEacces_SaysPermissionDenied()
    {
        var error = new UnauthorizedAccessException("Access to the port '/dev/ttyUSB3' is denied.", new IOException("Permission denied", 13));

        Assert.Equal(
            "/dev/ttyUSB3: permission denied (on Linux add the user to the dialout group)",
            SerialPortErrors.FromOpenFailure("/dev/ttyUSB3", error).Message);
    }

    [Fact]
    public void FromOpenFailure_OtherFailure_NamesThePortAndKeepsTheText()
    {
        var result = SerialPortErrors.FromOpenFailure("/dev/ttyUSB3", new InvalidOperationException("The port is already open."));

        Assert.Equal("/dev/ttyUSB3: cannot open: The port is already open.", result.Message);
    }
}

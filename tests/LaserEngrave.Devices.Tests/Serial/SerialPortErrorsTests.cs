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

    [Theory]
    [InlineData(2, "COM3: no such port")]
    [InlineData(5, "COM3: port is in use by another program")]
    [InlineData(32, "COM3: port is in use by another program")]
    public void FromWin32_KnownErrors_OneLineNamingThePort(int error, string message)
    {
        Assert.Equal(message, SerialPortErrors.FromWin32("COM3", error).Message);
    }

    [Fact]
    public void FromErrno_OtherError_KeepsThePortAndTheSystemText()
    {
        var message = SerialPortErrors.FromErrno("/dev/ttyS0", 5).Message;

        Assert.StartsWith("/dev/ttyS0: cannot open: ", message, StringComparison.Ordinal);
        Assert.True(message.Length > "/dev/ttyS0: cannot open: ".Length);
    }
}

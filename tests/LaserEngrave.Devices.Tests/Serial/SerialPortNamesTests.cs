using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Devices.Tests.Serial;

public sealed class SerialPortNamesTests
{
    [Fact]
    public void Sort_NumberedNames_NaturalOrderWithoutDuplicates()
    {
        var names = SerialPortNames.Sort(["COM10", "/dev/ttyUSB10", "COM2", "/dev/ttyUSB2", "/dev/ttyACM0", "COM2", "/dev/ttyS0"]);

        Assert.Equal(["/dev/ttyACM0", "/dev/ttyS0", "/dev/ttyUSB2", "/dev/ttyUSB10", "COM2", "COM10"], names);
    }

    [Fact]
    public void Sort_NameWithoutNumber_GoesBeforeTheNumberedOnesOfItsStem()
    {
        var names = SerialPortNames.Sort(["/dev/ttyUSB1", "/dev/ttyUSB"]);

        Assert.Equal(["/dev/ttyUSB", "/dev/ttyUSB1"], names);
    }

    [Fact]
    public void List_OnThisMachine_ReturnsDevicePathsInNaturalOrder()
    {
        var names = SerialPortNames.List();

        Assert.All(names, n => Assert.StartsWith("/dev/", n, StringComparison.Ordinal));
        Assert.Equal(names, SerialPortNames.Sort(names));
    }
}

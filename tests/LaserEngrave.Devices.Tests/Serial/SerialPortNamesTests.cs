using LaserEngrave.Devices.Serial;

namespace LaserEngrave.Devices.Tests.Serial;

public sealed class SerialPortNamesTests : IDisposable
{
    private readonly string _sys = Path.Combine(Path.GetTempPath(), $"le-sys-{Guid.NewGuid():N}");

    [Fact]
    public void ListLinux_SysClassTty_ListsTtysWithADeviceExceptEmptyUartSlots()
    {
        AddTty("ttyUSB0", withDevice: true, type: null);
        AddTty("ttyACM1", withDevice: true, type: null);
        AddTty("ttyS0", withDevice: true, type: "4");
        AddTty("ttyS1", withDevice: true, type: "0");
        AddTty("tty1", withDevice: false, type: null);
        AddTty("pts", withDevice: false, type: null);

        var names = SerialPortNames.ListLinux(_sys).Order(StringComparer.Ordinal).ToArray();

        Assert.Equal(["/dev/ttyACM1", "/dev/ttyS0", "/dev/ttyUSB0"], names);
    }

    [Fact]
    public void ListLinux_NoSysfs_ListsNothing()
    {
        Assert.Empty(SerialPortNames.ListLinux(Path.Combine(_sys, "absent")));
    }

    [Fact]
    public void List_OnThisMachine_ReturnsDevicePathsInNaturalOrder()
    {
        var names = SerialPortNames.List();

        Assert.All(names, n => Assert.StartsWith("/dev/", n, StringComparison.Ordinal));
        Assert.Equal(names.Count, names.Distinct().Count());
    }

    public void Dispose()
    {
        if (Directory.Exists(_sys))
        {
            Directory.Delete(_sys, recursive: true);
        }
    }

    private void AddTty(string name, bool withDevice, string? type)
    {
        var dir = Directory.CreateDirectory(Path.Combine(_sys, name)).FullName;
        if (withDevice)
        {
            Directory.CreateDirectory(Path.Combine(_sys, "devices", name));
            File.CreateSymbolicLink(Path.Combine(dir, "device"), Path.Combine(_sys, "devices", name));
        }

        if (type is not null)
        {
            File.WriteAllText(Path.Combine(dir, "type"), type + "\n");
        }
    }
}

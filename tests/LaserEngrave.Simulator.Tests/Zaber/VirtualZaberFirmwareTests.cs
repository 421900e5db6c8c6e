using LaserEngrave.Wire.Zaber;


namespace LaserEngrave.Simulator.Tests.Zaber;

/// <summary>The twin refuses what its firmware cannot do, as the manual says (zaber-binary.md §2, §6; docs/zaber-protocol.md's firmware table).</summary>
public class VirtualZaberFirmwareTests
{
    private static MachineBench Bench(int firmware, SimulatorOptions? options = null) =>
        MachineBench.Create((options ?? MachineBench.WireOnly) with { FirmwareVersion = firmware });

    [Theory(Timeout = 20_000)]
    [InlineData(502)]
    [InlineData(506)]
    [InlineData(519)]
    public async Task SetHomeSpeed_FirmwareBefore520_CommandInvalid64(int firmware)
    {
        await using var bench = Bench(firmware);

        var reply = await bench.RequestAsync(1, ZaberCommand.SetHomeSpeed, 4300);
        var read = await bench.RequestAsync(1, ZaberCommand.ReturnSetting, (int)ZaberCommand.SetHomeSpeed);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, ZaberErrorCodes.CommandInvalid), reply);
        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, ZaberErrorCodes.SettingInvalid), read);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(506, 4000)]
    [InlineData(523, 2000)]
    public async Task Home_RunsAtHomeSpeedFrom520AndAtTargetSpeedBefore(int firmware, int expectedSpeedData)
    {
        await using var bench = Bench(firmware, MachineBench.WireOnly with { TargetSpeedData = 4000, HomeSpeedData = 2000 });
        var travel = (double)LaserEngrave.Core.Geometry.MachineProfile.Default.X.TravelMicrosteps;
        var sent = bench.Now;

        await bench.SendAsync(1, ZaberCommand.Home, 0);
        var (reply, at) = await bench.ReceiveAsync(TimeSpan.FromMinutes(2));
        var seconds = (at - sent).TotalSeconds;

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Home, 0), reply);
        var cruise = travel / LaserEngrave.Core.Geometry.StageUnits.SpeedMicrostepsPerS(expectedSpeedData);
        Assert.InRange(seconds, cruise, cruise + 1);
    }

    [Fact(Timeout = 20_000)]
    public async Task EchoData_Firmware502_CommandInvalid64AndFrom504Echoes()
    {
        await using var old = Bench(502);
        await using var newer = Bench(504);

        Assert.Equal(new ZaberFrame(1, ZaberCommand.Error, ZaberErrorCodes.CommandInvalid), await old.RequestAsync(1, ZaberCommand.EchoData, 7));
        Assert.Equal(new ZaberFrame(1, ZaberCommand.EchoData, 7), await newer.RequestAsync(1, ZaberCommand.EchoData, 7));
    }

    [Theory(Timeout = 20_000)]
    [InlineData(521, true)]
    [InlineData(522, true)]
    [InlineData(506, false)]
    [InlineData(523, false)]
    public async Task SetTargetSpeedZero_521And522RefuseOthersTakeItAndRefuseTheMove(int firmware, bool refused)
    {
        await using var bench = Bench(firmware);

        var reply = await bench.RequestAsync(1, ZaberCommand.SetTargetSpeed, 0);
        var move = await bench.RequestAsync(1, ZaberCommand.MoveAbsolute, 1000);

        Assert.Equal(refused ? new ZaberFrame(1, ZaberCommand.Error, 42) : new ZaberFrame(1, ZaberCommand.SetTargetSpeed, 0), reply);
        Assert.Equal(refused ? new ZaberFrame(1, ZaberCommand.MoveAbsolute, 1000) : new ZaberFrame(1, ZaberCommand.Error, 20), move);
    }

    [Theory(Timeout = 20_000)]
    [InlineData(521, true)]
    [InlineData(506, false)]
    [InlineData(523, false)]
    public async Task SetMaximumPositionBelowCurrent_521And522Refuse(int firmware, bool refused)
    {
        await using var bench = Bench(firmware);

        // At power-up the axis stands at its maximum.
        var reply = await bench.RequestAsync(1, ZaberCommand.SetMaximumPosition, 300_000);

        Assert.Equal(refused ? new ZaberFrame(1, ZaberCommand.Error, 44) : new ZaberFrame(1, ZaberCommand.SetMaximumPosition, 300_000), reply);
    }

    [Fact(Timeout = 20_000)]
    public async Task ReturnFirmwareVersionAndDeviceId_AreTheOptions()
    {
        await using var bench = MachineBench.Create(MachineBench.WireOnly with { FirmwareVersion = 506, DeviceId = 1234 });

        Assert.Equal(new ZaberFrame(2, ZaberCommand.ReturnFirmwareVersion, 506), await bench.RequestAsync(2, ZaberCommand.ReturnFirmwareVersion, 0));
        Assert.Equal(new ZaberFrame(2, ZaberCommand.ReturnDeviceId, 1234), await bench.RequestAsync(2, ZaberCommand.ReturnDeviceId, 0));
    }

    [Theory]
    [InlineData("""{ "firmwareVersion": 506, "deviceId": 1234 }""", null)]
    [InlineData("""{ "firmwareVersion": 610 }""", "firmwareVersion 610 must be 500 to 599")]
    [InlineData("""{ "deviceId": 0 }""", "deviceId 0 must be 1 to")]
    public void OptionsFile_FirmwareAndDeviceId_ReadOrRefusedNamingTheField(string json, string? fragment)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            if (fragment is null)
            {
                var options = SimulatorOptionsFile.Load(path, new SimulatorOptions());
                Assert.Equal((506, 1234), (options.FirmwareVersion, options.DeviceId));
            }
            else
            {
                var ex = Assert.Throws<InvalidDataException>(() => SimulatorOptionsFile.Load(path, new SimulatorOptions()));
                Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
                Assert.Contains(path, ex.Message, StringComparison.Ordinal);
            }
        }
        finally
        {
            File.Delete(path);
        }
    }
}

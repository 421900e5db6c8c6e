using LaserEngrave.Core.Geometry;
using LaserEngrave.Simulator.Motion;
using LaserEngrave.Simulator.Zaber;
using LaserEngrave.Wire.Zaber;

namespace LaserEngrave.Simulator.Tests.Zaber;

/// <summary>The focus axis on the twin: a third device on the chain when the profile has a Z axis, none otherwise.</summary>
public class VirtualZAxisTests
{
    private static readonly MachineProfile ThreeAxis = MachineProfile.Default with { Z = new ZAxisProfile { DeviceNumber = 3, TravelMm = 25 } };

    [Fact(Timeout = 20_000)]
    public async Task Chain_ProfileWithZ_ThirdDeviceMovesOnItsOwnTrajectory()
    {
        await using var bench = MachineBench.Create(profile: ThreeAxis);
        var z = Assert.IsType<VirtualZaberDevice>(bench.Machine.Stage.Z);
        Assert.Equal((AxisName.Z, (byte)3, 2, ThreeAxis.Z!.TravelMicrosteps), (z.Axis, z.Number, z.ChainIndex, z.MaximumPosition));
        var xBefore = bench.Machine.Stage.X.Position;

        await bench.RequestAsync(3, ZaberCommand.Home, 0);
        var reply = await bench.RequestAsync(3, ZaberCommand.MoveAbsolute, 125_984);

        Assert.Equal(new ZaberFrame(3, ZaberCommand.MoveAbsolute, 125_984), reply);
        Assert.Equal(125_984, z.Position);
        Assert.Same(bench.Machine.Recorder.Z, z.Trajectory);
        Assert.Equal(xBefore, bench.Machine.Stage.X.Position);
    }

    [Fact(Timeout = 20_000)]
    public async Task Chain_DefaultProfile_TwoDevicesNoZ()
    {
        await using var bench = MachineBench.Create();

        Assert.Equal(2, bench.Machine.Stage.Devices.Count);
        Assert.Null(bench.Machine.Stage.Z);
        Assert.Null(bench.Machine.Recorder.Z);
        Assert.Null(bench.Machine.Recorder.FocusWhileFiring());
    }

    [Theory]
    [InlineData("""{ "trueFocusOffsetUm": 60, "rayleighLengthUm": 120 }""", null)]
    [InlineData("""{ "rayleighLengthUm": 0 }""", "rayleighLengthUm must be above 0 and at most 100000 µm (got 0)")]
    [InlineData("""{ "trueFocusOffsetUm": 1e9 }""", "trueFocusOffsetUm must be -100000..100000 µm")]
    public void OptionsFile_FocusFields_ReadOrRefusedNamingTheField(string json, string? fragment)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);
            if (fragment is null)
            {
                var options = SimulatorOptionsFile.Load(path, new SimulatorOptions());
                Assert.Equal((60.0, (double?)120), (options.TrueFocusOffsetUm, options.RayleighLengthUm));
            }
            else
            {
                var ex = Assert.Throws<InvalidDataException>(() => SimulatorOptionsFile.Load(path, new SimulatorOptions()));
                Assert.Contains(fragment, ex.Message, StringComparison.Ordinal);
            }
        }
        finally
        {
            File.Delete(path);
        }
    }
}

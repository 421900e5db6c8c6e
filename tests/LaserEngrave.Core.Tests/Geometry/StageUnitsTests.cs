using LaserEngrave.Core.Geometry;

namespace LaserEngrave.Core.Tests.Geometry;

public class StageUnitsTests
{
    [Fact]
    public void MmToMicrosteps_60mmOnTla_Is604724Point4()
    {
        Assert.Equal(604724.4, StageUnits.MmToMicrosteps(60, 0.09921875), 1);
        Assert.Equal(604724, MachineProfile.Default.X.TravelMicrosteps);
    }

    [Fact]
    public void SpeedData_4MmPerS_Is4300()
    {
        // 4 mm/s = 40314.96 microsteps/s = 4300.26 units of 9.375 microsteps/s.
        Assert.Equal(4300, StageUnits.SpeedData(4, 0.09921875));
        Assert.Equal(4300 * 9.375, StageUnits.SpeedMicrostepsPerS(4300));
    }

    [Fact]
    public void SignedSpeedData_HalfUnitsAndReverse_RoundAwayFromZeroWithinTheLimit()
    {
        // 2.5 units rounds away from zero (SpeedData rounds it to even, 2); the sign is kept; 0 is standing still.
        Assert.Equal(3, StageUnits.SignedSpeedData(2.5 * 9.375));
        Assert.Equal(-3, StageUnits.SignedSpeedData(-2.5 * 9.375));
        Assert.Equal(0, StageUnits.SignedSpeedData(0.4 * 9.375));
        Assert.Equal(-StageUnits.MaxSettingData, StageUnits.SignedSpeedData(-1e9));
        Assert.Equal(2, StageUnits.SpeedData(StageUnits.MicrostepsToMm(2.5 * 9.375, 0.09921875), 0.09921875));
    }

    [Fact]
    public void Profile_RoundTripsThroughJson()
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            var profile = MachineProfile.Default with { SpotDiameterUm = 35 };
            profile.Save(path);
            Assert.Equal(profile, MachineProfile.Load(path) with { X = profile.X, Y = profile.Y, Gate = profile.Gate });
            Assert.Equal(35, MachineProfile.Load(path).SpotDiameterUm);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_NegativeTravel_NamesTheFileAndTheValue()
    {
        var path = Path.Combine(Path.GetTempPath(), $"profile-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, """{ "x": { "deviceNumber": 1, "travelMm": -5 } }""");
            var ex = Assert.Throws<ProfileException>(() => MachineProfile.Load(path));
            Assert.Contains(path, ex.Message, StringComparison.Ordinal);
            Assert.Contains("x.travelMm", ex.Message, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }
}

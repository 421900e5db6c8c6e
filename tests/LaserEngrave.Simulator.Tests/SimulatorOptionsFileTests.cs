namespace LaserEngrave.Simulator.Tests;

public sealed class SimulatorOptionsFileTests
{
    [Theory]
    [InlineData("""{ "startMm": 0.5 }""", true, true)]
    [InlineData("""{ "paced": false }""", true, false)]
    [InlineData("""{ "paced": true }""", false, true)]
    public void Load_Paced_OverridesTheFrontEndsChoiceEitherWayOrKeepsIt(string json, bool basePaced, bool paced)
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, json);

            Assert.Equal(paced, SimulatorOptionsFile.Load(path, SimulatorOptions.FrontEnd with { Paced = basePaced }).Paced);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public void Load_PacedNotTrueOrFalse_RefusedNamingTheField()
    {
        var path = Path.Combine(Path.GetTempPath(), $"sim-{Guid.NewGuid():N}.json");
        try
        {
            File.WriteAllText(path, """{ "paced": "yes" }""");

            var ex = Assert.Throws<InvalidDataException>(() => SimulatorOptionsFile.Load(path, SimulatorOptions.FrontEnd));

            Assert.Contains("'paced'", ex.Message, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }
}

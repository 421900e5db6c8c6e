using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Marks;
using LaserEngrave.Core.Planning;
using LaserEngrave.Machines.Marks;

namespace LaserEngrave.Machines.Tests.Marks;

/// <summary>A code burned on the twin (its motion, switching and latencies in virtual time, every pulse a spot) read back by ZXing.</summary>
public class MarkReadabilityTests
{
    private static readonly OriginMm Origin = new(10, 10);

    [Fact(Timeout = 300_000)]
    public async Task CheckAsync_DataMatrixOfLargeModules_ReadsWithEveryModuleRight()
    {
        var code = CodeRaster.Render(CodeSymbol.Encode(CodeKind.DataMatrix, "S-001"), moduleUm: 60, quietModules: 1, spotDiameterUm: 20);

        var verdict = await MarkReadability.CheckAsync(code, MachineProfile.Default, ProcessSettings.Default, Origin, cancellationToken: TestContext.Current.CancellationToken);

        Assert.True(verdict.Reads, $"read \"{verdict.Decoded}\", {verdict.ModulesRight} of {verdict.Modules} modules right, worst {verdict.WorstModulePercent:0} %");
        Assert.Equal(verdict.Modules, verdict.ModulesRight);
        Assert.True(verdict.TwinSeconds > 0 && verdict.EstimatedSeconds > 0);
    }

    [Fact(Timeout = 300_000)]
    public async Task CheckAsync_ModulesOfOneSpot_DoNotReadAndSayWhy()
    {
        var code = CodeRaster.Render(CodeSymbol.Encode(CodeKind.DataMatrix, "S-001"), moduleUm: 20, quietModules: 1, spotDiameterUm: 20);

        var verdict = await MarkReadability.CheckAsync(code, MachineProfile.Default, ProcessSettings.Default, Origin, cancellationToken: TestContext.Current.CancellationToken);

        Assert.False(verdict.Reads, $"read \"{verdict.Decoded}\"");
        Assert.True(verdict.ModulesRight < verdict.Modules, $"{verdict.ModulesRight} of {verdict.Modules}");
    }

    [Fact(Timeout = 300_000)]
    public async Task SmallestReadableAsync_DefaultSpot_IsAboveOneSpotAndReads()
    {
        var smallest = await MarkReadability.SmallestReadableAsync(CodeKind.DataMatrix, "S-001", null, 1, MachineProfile.Default, ProcessSettings.Default, Origin, cancellationToken: TestContext.Current.CancellationToken);

        Assert.NotNull(smallest);
        Assert.InRange(smallest.Value.ModuleUm, 21, 100);
        Assert.True(smallest.Value.Verdict.Reads);
        TestContext.Current.TestOutputHelper?.WriteLine($"smallest readable module {smallest.Value.ModuleUm} µm");
    }

    [Fact]
    public void Burned_OnePulse_BurnsADiscOfTheSpotsDiameter()
    {
        // One pixel of 20 µm is 4 x 4 sub-cells of 5 µm; a pulse in the middle of a 10 x 10 pixel map.
        var counts = new int[40 * 40];
        counts[(20 * 40) + 20] = 1;
        var dose = new Simulator.Burn.DoseMap(10, 10, counts);

        var burned = MarkReadability.Burned(dose, pitchUm: 20, spotDiameterUm: 20);

        // A radius of 2 sub-cells: the 13 cells with i² + j² <= 4.
        Assert.Equal(13, burned.CountSet());
        Assert.True(burned[20, 20] && burned[22, 20] && burned[20, 18] && burned[21, 21]);
        Assert.False(burned[23, 20] || burned[20, 23] || burned[22, 22]);
    }
}

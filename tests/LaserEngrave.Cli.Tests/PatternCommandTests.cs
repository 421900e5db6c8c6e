using System.Text.Json;
using LaserEngrave.Core.Calibration;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

public class PatternCommandTests
{
    [Theory]
    [InlineData(".png")]
    [InlineData(".bmp")]
    public async Task PatternScanOffset_Out_WritesTheBarsThatLoadBack(string extension)
    {
        var path = CliHarness.TempFile(extension);
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("pattern", "scan-offset", "--out", path);

            Assert.True(exit == 0, error);
            Assert.Contains("Pattern: 5 bars 200 µm wide and 500 µm tall (20 rows), 300 µm apart; 88 x 20 px at 25 µm", output, StringComparison.Ordinal);
            var loaded = MaskBuilder.FromFile(path, MaskOptions.Default, out _);
            var expected = ScanOffsetPattern.Create(25, 200, 500, 5, 300).ToMask();
            Assert.Equal((expected.Width, expected.Height, expected.CountSet()), (loaded.Width, loaded.Height, loaded.CountSet()));
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task PatternScanOffset_SeveralSpeeds_OneEngraveLinePerSpeed_InOrder_EachBlockBelowTheLast()
    {
        var path = CliHarness.TempFile(".png");
        try
        {
            var (exit, output, error) = await CliHarness.RunAsync("pattern", "scan-offset", "--out", path, "--speed-mm-s", "2", "--speed-mm-s", "0.5", "--origin-mm", "5,6");

            Assert.True(exit == 0, error);
            var lines = output.Split('\n').Select(l => l.Trim()).Where(l => l.StartsWith("laserengrave engrave", StringComparison.Ordinal)).ToList();
            Assert.Equal(2, lines.Count);
            Assert.Contains("--origin-mm 5,6 --speed-mm-s 0.5 --bidirectional --overscan-mm 0.01", lines[0], StringComparison.Ordinal);

            // 0.5 mm tall blocks 0.5 mm apart; 2 mm/s at 50 mm/s² needs 2² / 100 = 0.04 mm to reach the speed.
            Assert.Contains("--origin-mm 5,7 --speed-mm-s 2 --bidirectional --overscan-mm 0.04", lines[1], StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
        }
    }

    [Fact]
    public async Task PatternScanOffset_ProfileWithOffsets_ShowsTheOffsetsTheEngravingApplies()
    {
        var (path, profile) = (CliHarness.TempFile(".png"), CliHarness.TempFile(".json"));
        try
        {
            (MachineProfile.Default with { ScanOffsets = [new ScanOffset(1, 4), new ScanOffset(3, 10)] }).Save(profile);

            var (exit, output, error) = await CliHarness.RunAsync("pattern", "scan-offset", "--out", path, "--speed-mm-s", "2", "--profile", profile);

            Assert.True(exit == 0, error);
            Assert.Contains("scan offsets: 7 µm at 2 mm/s", output, StringComparison.Ordinal);
            Assert.Contains("\"scanOffsets\": [ { \"speedMmPerS\": 2, \"offsetUm\": 7 } ]", output, StringComparison.Ordinal);
            Assert.Contains($"--profile {profile}", output, StringComparison.Ordinal);
        }
        finally
        {
            File.Delete(path);
            File.Delete(profile);
        }
    }

    [Fact]
    public async Task Plan_ProfileWithScanOffset_ShiftsTheReverseRowsOnly()
    {
        var (pattern, profile, plain, shifted) = (CliHarness.TempFile(".png"), CliHarness.TempFile(".json"), CliHarness.TempFile(".csv"), CliHarness.TempFile(".csv"));
        try
        {
            await CliHarness.RunAsync("pattern", "scan-offset", "--out", pattern);

            // 10 µm at every speed = 100.787 microsteps of 0.09921875 µm, added before the edges are rounded: 100 or 101.
            (MachineProfile.Default with { ScanOffsets = [new ScanOffset(1, 10)] }).Save(profile);
            await CliHarness.RunAsync("plan", pattern, "--pitch-um", "25", "--origin-mm", "10,10", "--segments", plain);
            var (exit, _, error) = await CliHarness.RunAsync("plan", pattern, "--pitch-um", "25", "--origin-mm", "10,10", "--profile", profile, "--segments", shifted);

            Assert.True(exit == 0, error);
            var (_, json, _) = await CliHarness.RunAsync("plan", pattern, "--pitch-um", "25", "--origin-mm", "10,10", "--profile", profile, "--json");
            using (var document = JsonDocument.Parse(json))
            {
                Assert.Equal(10, document.RootElement.GetProperty("scanOffsetUm").GetDouble());
            }

            var before = Burns(plain);
            var after = Burns(shifted);
            Assert.Equal(before.Count, after.Count);
            for (var i = 0; i < before.Count; i++)
            {
                var leftToRight = before[i][2] > before[i][0];
                Assert.InRange(after[i][0] - before[i][0], leftToRight ? 0 : 100, leftToRight ? 0 : 101);
                Assert.InRange(after[i][2] - before[i][2], leftToRight ? 0 : 100, leftToRight ? 0 : 101);
                Assert.Equal(before[i][1], after[i][1]);
            }
        }
        finally
        {
            foreach (var file in new[] { pattern, profile, plain, shifted })
            {
                File.Delete(file);
            }
        }
    }

    private static List<long[]> Burns(string csv) =>
        [.. File.ReadAllLines(csv).Where(l => l.StartsWith("burn,", StringComparison.Ordinal)).Select(l => l.Split(',').Skip(1).Select(long.Parse).ToArray())];
}

using System.Text.Json;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

public class AlignCommandTests
{
    [Fact]
    public async Task Align_MarksOfAQuarterTurn_WritesTheTurnedMaskAndItsOrigin()
    {
        var image = CliHarness.BmpSuite("g/pal1.bmp");
        var output = CliHarness.TempFile(".bmp");
        try
        {
            // At 10 µm per pixel, job (0,0) found at stage (30,10) and job (1,0) at (30,11): +x turned onto +y, 90°.
            var (exit, stdout, error) = await CliHarness.RunAsync(
                "align", image, "--pitch-um", "10", "--mark", "0,0=30,10", "--mark", "1,0=30,11", "--out", output, "--json");

            Assert.True(exit == 0, error);
            using var json = JsonDocument.Parse(stdout);
            Assert.Equal(90, json.RootElement.GetProperty("rotationDegrees").GetDouble(), 9);
            var job = MaskBuilder.FromFile(image, MaskOptions.Default, out _);
            var turned = MaskBuilder.FromFile(output, MaskOptions.Default, out _);
            Assert.Equal((job.Height, job.Width), (turned.Width, turned.Height));
            Assert.Equal(job.CountSet(), turned.CountSet());
            Assert.True(job[5, 7] == turned[job.Height - 1 - 7, 5]);

            // The turned job spans stage x from 30 - height x 10 µm to 30.
            Assert.Equal(30 - (job.Height * 0.01), json.RootElement.GetProperty("originXMm").GetDouble(), 9);
            Assert.Equal(10, json.RootElement.GetProperty("originYMm").GetDouble(), 9);
        }
        finally
        {
            File.Delete(output);
        }
    }

    [Theory]
    [InlineData("0,0=30,10", "5,0=35.2,10")]
    [InlineData("0,0=30,10", "5,0")]
    [InlineData("0,0=30,10", "0.1,0=30.1,10")]
    public async Task Align_BadMarks_OneLineExitTwo(string first, string second)
    {
        var output = CliHarness.TempFile(".png");
        var (exit, _, error) = await CliHarness.RunAsync(
            "align", CliHarness.BmpSuite("g/pal1.bmp"), "--pitch-um", "10", "--mark", first, "--mark", second, "--out", output);

        Assert.Equal(2, exit);
        Assert.Single(error.Split('\n', StringSplitOptions.RemoveEmptyEntries));
        Assert.False(File.Exists(output));
    }
}

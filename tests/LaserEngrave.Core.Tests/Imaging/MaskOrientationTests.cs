using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;

namespace LaserEngrave.Core.Tests.Imaging;

/// <summary>Rotate and mirror of a burn mask: the picture on the stage turns and flips, the plan is made from it.</summary>
public class MaskOrientationTests
{
    // 3 x 2:  X . .
    //         X X .
    private static BitMask L()
    {
        var mask = new BitMask(3, 2);
        mask[0, 0] = true;
        mask[0, 1] = true;
        mask[1, 1] = true;
        return mask;
    }

    private static string Text(BitMask m) => string.Join("/", Enumerable.Range(0, m.Height).Select(y => string.Concat(Enumerable.Range(0, m.Width).Select(x => m[x, y] ? 'X' : '.'))));

    [Theory]
    [InlineData(0, false, false, "X../XX.")]
    [InlineData(1, false, false, "XX/X./..")]
    [InlineData(2, false, false, ".XX/..X")]
    [InlineData(3, false, false, "../.X/XX")]
    [InlineData(0, true, false, "..X/.XX")]
    [InlineData(0, false, true, "XX./X..")]
    [InlineData(1, true, false, "../X./XX")]
    public void Apply_TurnsAndMirrors_AsSeenOnTheStage(int turns, bool mirrorX, bool mirrorY, string expected)
    {
        var result = MaskOrientation.Apply(L(), new MaskOptions { QuarterTurns = turns, MirrorX = mirrorX, MirrorY = mirrorY });

        Assert.Equal(expected, Text(result));
    }

    [Fact]
    public void Validate_FiveQuarterTurns_Refused()
    {
        Assert.Throws<ArgumentOutOfRangeException>(() => new MaskOptions { QuarterTurns = 5 }.Validate());
    }

    [Fact]
    public void JobFile_TurnedMirroredLayer_ReadsBackTheSame()
    {
        var folder = Directory.CreateTempSubdirectory();
        try
        {
            var path = Path.Combine(folder.FullName, "job.json");
            var layer = new JobLayer
            {
                Name = "qr",
                Source = StarterAssetsTests.Asset("qr-code.bmp"),
                Mode = LayerMode.Raster,
                WidthMm = 5,
                Mask = new MaskOptions { QuarterTurns = 3, MirrorY = true },
            };

            JobFile.Save(path, [layer]);

            Assert.Equal(layer, Assert.Single(JobFile.Load(path)));
        }
        finally
        {
            folder.Delete(recursive: true);
        }
    }
}

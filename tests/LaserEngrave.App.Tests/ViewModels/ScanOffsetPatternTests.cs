using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Imaging;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Planning;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class ScanOffsetPatternTests
{
    [Fact]
    public void LoadScanOffsetPattern_OpensTheBarsBidirectionalAtTheBurnSpeedWithARunUp()
    {
        using var folder = TestFiles.NewFolder();
        var (main, files) = Start(folder.Path);
        main.Job.BurnSpeedMmPerS = 2;

        Assert.True(main.LoadScanOffsetPattern());

        var written = Path.Combine(folder.Path, "scan-offset.png");
        files.Received(1).SavePattern("scan-offset", Arg.Any<BitMask>());
        Assert.Equal(written, main.Job.ImagePath);
        Assert.Equal(SizeMode.Pitch, main.Job.SizeMode);
        Assert.Equal(25, main.Job.PitchUm, 9);
        Assert.True(main.Job.Bidirectional);
        Assert.Equal(PlanStrategy.Optimized, main.Job.Strategy);

        // 2 mm/s at the default 50 mm/s²: 0.04 mm to reach the speed.
        Assert.Equal(0.04, main.Job.OverscanMm, 9);
        var job = Assert.IsType<Core.Jobs.PreparedJob>(main.Job.Job);
        Assert.True(job.Mask.CountSet() > 0);
        Assert.Equal(0, job.Mask.Height % 2);
    }

    [Fact]
    public void LoadScanOffsetPattern_FolderNotWritable_SaysSoAndKeepsTheJob()
    {
        using var folder = TestFiles.NewFolder();
        var (main, files) = Start(folder.Path);
        main.Job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        files.SavePattern(Arg.Any<string>(), Arg.Any<BitMask>()).Returns(_ => throw new UnauthorizedAccessException("access denied"));

        Assert.False(main.LoadScanOffsetPattern());

        Assert.Equal("the scan offset pattern could not be written: access denied", main.PatternError);
        Assert.Equal(TestFiles.Asset("qr-code.bmp"), main.Job.ImagePath);
    }

    private static (MainViewModel Main, IFileAccess Files) Start(string folder)
    {
        var files = Substitute.For<IFileAccess>();
        files.SampleImages().Returns([]);
        files.SavePattern(Arg.Any<string>(), Arg.Any<BitMask>()).Returns(c =>
        {
            var path = Path.Combine(folder, c.Arg<string>() + ".png");
            PngWriter.WriteMask(path, c.Arg<BitMask>());
            return path;
        });
        var logs = Substitute.For<IRunLogStore>();
        logs.History().Returns([]);
        var store = new JsonSettingsStore(Path.Combine(folder, "settings.json"));
        return (new MainViewModel(new ImageService(), new Fakes().Factory, Substitute.For<IRunService>(), logs, store, files, TimeProvider.System, new MachineActivity()), files);
    }
}

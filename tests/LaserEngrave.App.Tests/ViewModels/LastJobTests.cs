using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class LastJobTests
{
    [Fact]
    public async Task Restart_LastJobsSizePositionAndProcessRemembered()
    {
        using var folder = TestFiles.NewFolder();
        var store = new JsonSettingsStore(Path.Combine(folder.Path, "settings.json"));
        var files = Substitute.For<IFileAccess>();
        files.Exists(Arg.Any<string>()).Returns(c => File.Exists(c.Arg<string>()));
        files.SampleImages().Returns([]);
        var logs = Substitute.For<IRunLogStore>();
        logs.History().Returns([]);
        async Task<MainViewModel> Start()
        {
            var main = new MainViewModel(new ImageService(), new Fakes().Factory, Substitute.For<IRunService>(), logs, store, files, TimeProvider.System, new MachineActivity());
            await main.Restore();
            return main;
        }

        var first = await Start();
        first.Job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        first.Job.EditWidth(7.5);
        first.Job.Batch(() =>
        {
            first.Job.OriginXMm = 20.25;
            first.Job.BurnSpeedMmPerS = 2;
            first.Job.Passes = 3;
        });

        var second = await Start();

        Assert.Equal(TestFiles.Asset("qr-code.bmp"), second.Job.ImagePath);
        Assert.Equal((7.5, 20.25, 2.0, 3), (second.Job.WidthMm, second.Job.OriginXMm, second.Job.BurnSpeedMmPerS, second.Job.Passes));
        Assert.NotNull(second.Job.Job);
    }

    [Fact]
    public async Task Restart_LastJobTurnedAndMirrored_OpensAsItWasNotUpright()
    {
        using var folder = TestFiles.NewFolder();
        var store = new JsonSettingsStore(Path.Combine(folder.Path, "settings.json"));
        var files = Substitute.For<IFileAccess>();
        files.Exists(Arg.Any<string>()).Returns(c => File.Exists(c.Arg<string>()));
        files.SampleImages().Returns([]);
        var logs = Substitute.For<IRunLogStore>();
        logs.History().Returns([]);
        async Task<MainViewModel> Start()
        {
            var main = new MainViewModel(new ImageService(), new Fakes().Factory, Substitute.For<IRunService>(), logs, store, files, TimeProvider.System, new MachineActivity());
            await main.Restore();
            return main;
        }

        var first = await Start();
        first.Job.LoadImage(TestFiles.Asset("text-banner.png"));
        first.Job.Rotate(clockwise: true);
        first.Job.FlipVertical();

        // Another file opens upright (issue 36); the same job after a restart is the job it was.
        var second = await Start();

        Assert.Equal((1, true, false), (second.Job.QuarterTurns, second.Job.MirrorX, second.Job.MirrorY));
        Assert.Equal((60, 308), (second.Job.Mask!.Width, second.Job.Mask.Height));
    }

    [Fact]
    public async Task Restart_LastImageSlowToRead_OpensInTheBackgroundWithItsProgress()
    {
        using var folder = TestFiles.NewFolder();
        var store = new JsonSettingsStore(Path.Combine(folder.Path, "settings.json"));
        var banner = TestFiles.Asset("text-banner.png");
        store.Save(new AppSettings { RecentFiles = [banner] });
        var files = Substitute.For<IFileAccess>();
        files.Exists(Arg.Any<string>()).Returns(c => File.Exists(c.Arg<string>()));
        files.SampleImages().Returns([]);
        var logs = Substitute.For<IRunLogStore>();
        logs.History().Returns([]);
        var images = new GatedImages { GatedName = "text-banner.png" };
        var main = new MainViewModel(images, new Fakes().Factory, Substitute.For<IRunService>(), logs, store, files, TimeProvider.System, new MachineActivity());

        var restoring = main.Restore();

        // The app's start (and its first page) does not wait for the image: it shows what is being read.
        Assert.False(restoring.IsCompleted);
        Assert.Equal("Reading text-banner.png…", main.Job.LoadingLine);
        Assert.Null(main.Job.ImagePath);
        images.Gate.SetResult();
        await restoring.WaitAsync(TimeSpan.FromSeconds(30), TestContext.Current.CancellationToken);
        Assert.Equal(banner, main.Job.ImagePath);
        Assert.Null(main.Job.LoadingLine);
        Assert.NotNull(main.Job.Job);
    }
}

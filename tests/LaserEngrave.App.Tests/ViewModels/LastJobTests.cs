using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class LastJobTests
{
    [Fact]
    public void Restart_LastJobsSizePositionAndProcessRemembered()
    {
        using var folder = TestFiles.NewFolder();
        var store = new JsonSettingsStore(Path.Combine(folder.Path, "settings.json"));
        var files = Substitute.For<IFileAccess>();
        files.Exists(Arg.Any<string>()).Returns(c => File.Exists(c.Arg<string>()));
        files.SampleImages().Returns([]);
        var logs = Substitute.For<IRunLogStore>();
        logs.History().Returns([]);
        MainViewModel Start()
        {
            var main = new MainViewModel(new ImageService(), new Fakes().Factory, Substitute.For<IRunService>(), logs, store, files, TimeProvider.System, new MachineActivity());
            main.Restore();
            return main;
        }

        var first = Start();
        first.Job.LoadImage(TestFiles.Asset("qr-code.bmp"));
        first.Job.EditWidth(7.5);
        first.Job.Batch(() =>
        {
            first.Job.OriginXMm = 20.25;
            first.Job.BurnSpeedMmPerS = 2;
            first.Job.Passes = 3;
        });

        var second = Start();

        Assert.Equal(TestFiles.Asset("qr-code.bmp"), second.Job.ImagePath);
        Assert.Equal((7.5, 20.25, 2.0, 3), (second.Job.WidthMm, second.Job.OriginXMm, second.Job.BurnSpeedMmPerS, second.Job.Passes));
        Assert.NotNull(second.Job.Job);
    }
}

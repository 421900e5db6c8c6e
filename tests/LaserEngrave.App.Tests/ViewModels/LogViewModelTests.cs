using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using NSubstitute;
using NSubstitute.ExceptionExtensions;

namespace LaserEngrave.App.Tests.ViewModels;

public sealed class LogViewModelTests
{
    private readonly IRunLogStore _store = Substitute.For<IRunLogStore>();
    private readonly IFileAccess _files = Substitute.For<IFileAccess>();
    private readonly JobViewModel _job = new(new ImageService(), MachineProfile.Default);
    private readonly LogViewModel _log;

    public LogViewModelTests()
    {
        _log = new LogViewModel(_store, _files, _job);
        _store.Folder.Returns("/logs");
    }

    private static RunRecord Record(string id, string? image) => new()
    {
        Id = id,
        StartedUtc = DateTimeOffset.UnixEpoch,
        Outcome = "completed",
        Machine = "fake",
        SampleId = "S-" + id,
        Settings = new JobSettings { ImagePath = image, WidthMm = 3, Passes = 2, BurnSpeedMmPerS = 2 },
    };

    [Fact]
    public void Load_PastRun_SettingsAndImageBackInJob()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        _store.History().Returns([Record("a", image)]);
        _files.Exists(image).Returns(true);
        _log.RefreshCommand.Execute(null);

        _log.LoadCommand.Execute("a");

        Assert.Null(_log.Error);
        Assert.Equal(image, _job.ImagePath);
        Assert.Equal(3, _job.WidthMm, 6);
        Assert.Equal(2, _job.Passes);
        Assert.Equal("S-a", _log.SampleId);
    }

    [Fact]
    public void Load_ImageGone_SettingsLoadedAndErrorNamesImage()
    {
        _store.History().Returns([Record("b", "/gone/x.png")]);
        _log.RefreshCommand.Execute(null);

        _log.LoadCommand.Execute("b");

        Assert.Contains("/gone/x.png", _log.Error, StringComparison.Ordinal);
        Assert.Equal(2, _job.Passes);
    }

    [Fact]
    public void Load_UnknownId_Error()
    {
        _store.History().Returns([]);

        _log.LoadCommand.Execute("nope");

        Assert.Equal("run nope is not in the history", _log.Error);
    }

    [Fact]
    public void Record_StoreFails_ErrorNamesFolderAndLastRunKept()
    {
        _store.When(s => s.Save(Arg.Any<RunRecord>())).Throw(new IOException("disk full"));

        _log.Record(Record("c", null));

        Assert.Contains("/logs", _log.Error, StringComparison.Ordinal);
        Assert.Equal("c", _log.LastRun!.Id);
    }

    [Fact]
    public void OpenFolder_ShellFails_Error()
    {
        _files.When(f => f.OpenFolder("/logs")).Throw(new InvalidOperationException("no file manager"));

        _log.OpenFolderCommand.Execute(null);

        Assert.Contains("no file manager", _log.Error, StringComparison.Ordinal);
    }

    [Fact]
    public void ToText_Record_NamesSampleAndOutcome()
    {
        var text = Record("d", "/img.png").ToText();

        Assert.Contains("sample       S-d", text, StringComparison.Ordinal);
        Assert.Contains("outcome      completed", text, StringComparison.Ordinal);
    }
}

using LaserEngrave.App.Services;
using LaserEngrave.App.ViewModels;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Logging;
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

    private static RunRecord Record(string image, string sha)
    {
        var job = PreparedJob.Prepare(new JobSpec { ImagePath = image, Size = SizeSpec.Width(3), Origin = new OriginMm(2, 4) });
        return RunRecord.ForJob(job, sha, DateTimeOffset.UnixEpoch) with { Outcome = RunOutcome.Completed, SampleId = "S-1", Notes = "n" };
    }

    [Fact]
    public void Load_PastRun_SettingsAndImageBackInJob()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        _store.History().Returns([new RunLogEntry("/logs/a.json", Record(image, PreparedJob.HashFile(image)), null)]);
        _log.RefreshCommand.Execute(null);

        _log.LoadCommand.Execute("/logs/a.json");

        Assert.Null(_log.Error);
        Assert.Equal(image, _job.ImagePath);
        Assert.Equal(3, _job.WidthMm, 6);
        Assert.Equal((2.0, 4.0), (_job.OriginXMm, _job.OriginYMm));
        Assert.Equal("S-1", _log.SampleId);
        Assert.Null(_log.Notice);
    }

    [Fact]
    public void Load_PastRunWithAnotherProfile_NoticeNamesBothProfiles()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        var record = Record(image, PreparedJob.HashFile(image));
        record = record with { Profile = record.Profile with { Name = "Lab B stage" } };
        _store.History().Returns([new RunLogEntry("/logs/d.json", record, null)]);
        _log.RefreshCommand.Execute(null);

        _log.LoadCommand.Execute("/logs/d.json");

        Assert.Null(_log.Error);
        Assert.Contains("\"Lab B stage\"", _log.Notice, StringComparison.Ordinal);
        Assert.Contains(_job.Profile.Name, _log.Notice, StringComparison.Ordinal);
    }

    [Fact]
    public void Load_ImageChanged_ErrorAndNothingLoaded()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        _store.History().Returns([new RunLogEntry("/logs/b.json", Record(image, new string('0', 64)), null)]);
        _log.RefreshCommand.Execute(null);

        _log.LoadCommand.Execute("/logs/b.json");

        Assert.Contains("has changed", _log.Error, StringComparison.Ordinal);
        Assert.Null(_job.ImagePath);
    }

    [Fact]
    public void Load_UnknownPath_Error()
    {
        _store.History().Returns([]);

        _log.LoadCommand.Execute("/etc/passwd");

        Assert.Equal("/etc/passwd: not a run in the history", _log.Error);
    }

    [Fact]
    public void Record_StoreFails_ErrorNamesFolderAndLastRunKept()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        _store.Save(Arg.Any<RunRecord>()).Throws(new RunLogException("/logs: disk full"));

        _log.Record(Record(image, "abc"));

        Assert.Contains("/logs", _log.Error, StringComparison.Ordinal);
        Assert.Equal("S-1", _log.LastRun!.Record!.SampleId);
    }

    [Fact]
    public void Record_LogFolderFailedAndTheLogWentToTheDataFolder_ErrorIsTheOneLineSayingWhere()
    {
        // Issue 31 finding 6: the app shows where the record that resumes the run went, and why.
        var image = TestFiles.Asset("qr-code.bmp");
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/data/c.json", "/data/c.txt") { FallbackReason = "/logs/c.json: cannot write the run log: Read-only file system" });

        _log.Record(Record(image, "abc"));

        Assert.Equal("the run log is in /data/c.json instead: /logs/c.json: cannot write the run log: Read-only file system", _log.Error);
        Assert.Equal("/data/c.json", _log.LastRun!.Path);
    }

    [Fact]
    public void RunLogFolder_LogFolderBecameAFile_SavesInTheDataFolder()
    {
        var root = Path.Combine(Path.GetTempPath(), $"le-app-logfallback-{Guid.NewGuid():N}");
        var logs = Path.Combine(root, "logs");
        Directory.CreateDirectory(root);
        try
        {
            var folder = new RunLogFolder(logs, Path.Combine(root, "data"));
            folder.CheckWritable();
            Directory.Delete(logs);
            File.WriteAllText(logs, "a file where the log folder was");

            var files = folder.Save(Record(TestFiles.Asset("qr-code.bmp"), "abc"));

            Assert.Equal(Path.Combine(root, "data"), Path.GetDirectoryName(files.JsonPath));
            Assert.StartsWith($"the run log is in {files.JsonPath} instead: {logs}: ", files.Notice, StringComparison.Ordinal);
        }
        finally
        {
            Directory.Delete(root, recursive: true);
        }
    }

    [Fact]
    public void Record_Saved_LastRunNamesItsFileAndHistoryRefreshed()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        _store.Save(Arg.Any<RunRecord>()).Returns(new RunLogFiles("/logs/c.json", "/logs/c.txt"));

        _log.Record(Record(image, "abc"));

        Assert.Equal("/logs/c.json", _log.LastRun!.Path);
        _store.Received(1).History();
    }

    [Fact]
    public void OpenFolder_ShellFails_Error()
    {
        _files.When(f => f.OpenFolder("/logs")).Throw(new InvalidOperationException("no file manager"));

        _log.OpenFolderCommand.Execute(null);

        Assert.Contains("no file manager", _log.Error, StringComparison.Ordinal);
    }

    private void ThreeRuns()
    {
        var image = TestFiles.Asset("qr-code.bmp");
        var sha = PreparedJob.HashFile(image);
        _store.History().Returns(
        [
            new RunLogEntry("/logs/c.json", Record(image, sha) with { SampleId = "Si-3", StartedAt = DateTimeOffset.UnixEpoch.AddDays(3), ActualSeconds = 30 }, null),
            new RunLogEntry("/logs/bad.json", null, "not a run log"),
            new RunLogEntry("/logs/b.json", Record(image, sha) with { SampleId = "Si-2", StartedAt = DateTimeOffset.UnixEpoch.AddDays(2), ActualSeconds = 90, Outcome = RunOutcome.Aborted }, null),
            new RunLogEntry("/logs/a.json", Record(image, sha) with { SampleId = "Glass-1", StartedAt = DateTimeOffset.UnixEpoch.AddDays(1), ActualSeconds = 60 }, null),
        ]);
        _log.RefreshCommand.Execute(null);
    }

    [Fact]
    public void Rows_SearchedAndSorted_TheTableFollows()
    {
        ThreeRuns();
        Assert.Equal(["/logs/c.json", "/logs/b.json", "/logs/a.json"], _log.Rows.Select(r => r.Path));

        _log.Search = "si-";
        Assert.Equal(["/logs/c.json", "/logs/b.json"], _log.Rows.Select(r => r.Path));

        _log.Search = "aborted";
        Assert.Equal("/logs/b.json", Assert.Single(_log.Rows).Path);

        _log.Search = null;
        _log.SortCommand.Execute("duration");
        Assert.Equal([90.0, 60, 30], _log.Rows.Select(r => r.ActualSeconds));
        _log.SortCommand.Execute("duration");
        Assert.Equal([30.0, 60, 90], _log.Rows.Select(r => r.ActualSeconds));
        _log.SortCommand.Execute("sample ID");
        Assert.Equal(["Glass-1", "Si-2", "Si-3"], _log.Rows.Select(r => r.SampleId));
    }

    [Fact]
    public void Rows_ReadAgain_TheSameTableUntilTheHistorySearchOrSortChanges()
    {
        ThreeRuns();
        var rows = _log.Rows;
        _log.ToggleSelectedCommand.Execute("/logs/a.json");
        var selected = _log.SelectedRows;

        // A render reads the rows several times: they are made once, not once per read.
        Assert.Same(rows, _log.Rows);
        Assert.Same(selected, _log.SelectedRows);
        _log.Search = "si-";
        var searched = _log.Rows;
        Assert.NotSame(rows, searched);
        Assert.Empty(_log.SelectedRows);
        _log.SortCommand.Execute("duration");
        var sorted = _log.Rows;
        Assert.NotSame(searched, sorted);
        ThreeRuns();
        Assert.NotSame(sorted, _log.Rows);
        Assert.Equal(2, _log.Rows.Count);
    }

    [Fact]
    public void Export_TickedRuns_OnlyThoseInTheTablesOrder()
    {
        ThreeRuns();
        _log.ToggleSelectedCommand.Execute("/logs/a.json");
        _log.ToggleSelectedCommand.Execute("/logs/c.json");
        _log.ToggleSelectedCommand.Execute("/logs/b.json");
        _log.ToggleSelectedCommand.Execute("/logs/b.json");

        var lines = _log.Export("csv", decimalComma: true).TrimEnd().Split("\r\n");

        Assert.Equal(3, lines.Length);
        Assert.Contains(";Si-3;", lines[1], StringComparison.Ordinal);
        Assert.Contains(";Glass-1;", lines[2], StringComparison.Ordinal);
        Assert.Equal(2, System.Text.Json.JsonDocument.Parse(_log.Export("json", decimalComma: false)).RootElement.GetArrayLength());
        _log.ClearSelectionCommand.Execute(null);
        Assert.Empty(_log.SelectedRows);
        _log.Search = "si";
        _log.SelectShownCommand.Execute(null);
        Assert.Equal(2, _log.SelectedRows.Count);
    }
}

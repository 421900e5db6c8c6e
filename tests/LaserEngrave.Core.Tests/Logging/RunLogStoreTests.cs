using LaserEngrave.Core.Logging;

namespace LaserEngrave.Core.Tests.Logging;

public sealed class RunLogStoreTests : IDisposable
{
    private readonly TestRuns runs = new();

    private string LogFolder => Path.Combine(runs.Folder, "logs");

    [Fact]
    public void Write_NewFolder_WritesJsonAndTextNamedByStartTimeAndSample()
    {
        var store = new RunLogStore(LogFolder);

        var files = store.Write(runs.FailedRecord());

        Assert.Equal(Path.Combine(LogFolder, "2026-11-23_143005_S-17.json"), files.JsonPath);
        Assert.Equal(Path.Combine(LogFolder, "2026-11-23_143005_S-17.txt"), files.TextPath);
        Assert.Equal(runs.FailedRecord().Image, RunLogStore.Read(files.JsonPath).Image);
        Assert.Contains("S-17", File.ReadAllText(files.TextPath), StringComparison.Ordinal);
    }

    [Fact]
    public void Write_SameNameThreeTimes_AddsSuffixesAndNeverOverwrites()
    {
        var store = new RunLogStore(LogFolder);
        var first = store.Write(runs.FailedRecord() with { Notes = "one" });

        var second = store.Write(runs.FailedRecord() with { Notes = "two" });
        var third = store.Write(runs.FailedRecord() with { Notes = "three" });

        Assert.EndsWith("_S-17-2.json", second.JsonPath, StringComparison.Ordinal);
        Assert.EndsWith("_S-17-3.txt", third.TextPath, StringComparison.Ordinal);
        Assert.Equal("one", RunLogStore.Read(first.JsonPath).Notes);
        Assert.Equal("two", RunLogStore.Read(second.JsonPath).Notes);
        Assert.Equal("three", RunLogStore.Read(third.JsonPath).Notes);
    }

    [Fact]
    public void Write_OnlyTheTextNameTaken_SkipsThePairAndLeavesTheFileAlone()
    {
        Directory.CreateDirectory(LogFolder);
        var taken = Path.Combine(LogFolder, "2026-11-23_143005_S-17.txt");
        File.WriteAllText(taken, "someone's notes");

        var files = new RunLogStore(LogFolder).Write(runs.FailedRecord());

        Assert.EndsWith("_S-17-2.json", files.JsonPath, StringComparison.Ordinal);
        Assert.Equal("someone's notes", File.ReadAllText(taken));
        Assert.False(File.Exists(Path.ChangeExtension(taken, ".json")));
    }

    [Theory]
    [InlineData(null, "2026-11-23_143005")]
    [InlineData("  ", "2026-11-23_143005")]
    [InlineData("../etc/passwd", "2026-11-23_143005__etc_passwd")]
    [InlineData("..", "2026-11-23_143005")]
    [InlineData("Probe 3: Si/SiO2", "2026-11-23_143005_Probe_3__Si_SiO2")]
    public void FileStem_SampleId_MadeSafeForAFileName(string? sample, string expected)
    {
        Assert.Equal(expected, RunLogStore.FileStem(runs.FailedRecord(sample)));
    }

    [Fact]
    public void List_SeveralRunsAndABadFile_NewestFirstThenTheBadOneWithItsError()
    {
        var store = new RunLogStore(LogFolder);
        var older = store.Write(runs.FailedRecord("old") with { StartedAt = TestRuns.Start.AddDays(-1) });
        var newer = store.Write(runs.FailedRecord("new"));
        File.WriteAllText(Path.Combine(LogFolder, "broken.json"), "{ not json");

        var entries = store.List();

        Assert.Equal([newer.JsonPath, older.JsonPath, Path.Combine(LogFolder, "broken.json")], entries.Select(e => e.Path));
        Assert.Equal("new", entries[0].Record?.SampleId);
        Assert.Null(entries[2].Record);
        Assert.StartsWith(Path.Combine(LogFolder, "broken.json") + ": not a run log", entries[2].Error, StringComparison.Ordinal);
    }

    [Fact]
    public void Write_FolderUnderAFile_ThrowsOneLineNamingTheFolder()
    {
        var file = Path.Combine(runs.Folder, "a-file");
        File.WriteAllText(file, "x");
        var store = new RunLogStore(Path.Combine(file, "logs"));

        var ex = Assert.Throws<RunLogException>(() => store.Write(runs.FailedRecord()));

        Assert.StartsWith($"{store.Folder}: cannot create the log folder", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public void List_FolderMissing_IsEmpty()
    {
        Assert.Empty(new RunLogStore(Path.Combine(runs.Folder, "nothing-here")).List());
    }

    [Fact]
    public void Read_MissingFile_OneLineSayingSo()
    {
        var path = Path.Combine(runs.Folder, "gone.json");

        var ex = Assert.Throws<RunLogException>(() => RunLogStore.Read(path));

        Assert.Equal($"{path}: no such run log", ex.Message);
    }

    [Fact]
    public void Read_TextSummaryPath_ReadsTheJsonBesideIt()
    {
        var files = new RunLogStore(LogFolder).Write(runs.FailedRecord());

        Assert.Equal("S-17", RunLogStore.Read(files.TextPath).SampleId);
    }

    [Fact]
    public void DefaultFolderFrom_DocumentsKnown_IsLaserEngraveUnderDocuments()
    {
        var folder = RunLogStore.DefaultFolderFrom(f => f == Environment.SpecialFolder.MyDocuments ? "/home/ana/Documents" : "/home/ana", "/work");

        Assert.Equal(Path.Combine("/home/ana/Documents", "LaserEngrave"), folder);
    }

    [Fact]
    public void DefaultFolderFrom_NoDocumentsFolder_FallsBackToDocumentsUnderHome()
    {
        var folder = RunLogStore.DefaultFolderFrom(f => f == Environment.SpecialFolder.UserProfile ? "/home/ana" : string.Empty, "/work");

        Assert.Equal(Path.Combine("/home/ana", "Documents", "LaserEngrave"), folder);
    }

    [Fact]
    public void DefaultFolderFrom_NoHomeEither_FallsBackToTheCurrentDirectory()
    {
        Assert.Equal(Path.Combine("/work", "LaserEngrave"), RunLogStore.DefaultFolderFrom(_ => string.Empty, "/work"));
    }

    public void Dispose() => runs.Dispose();
}

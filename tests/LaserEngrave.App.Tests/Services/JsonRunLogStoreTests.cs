using LaserEngrave.App.Services;

namespace LaserEngrave.App.Tests.Services;

public sealed class JsonRunLogStoreTests
{
    [Fact]
    public void Save_TwoRuns_HistoryNewestFirst()
    {
        using var folder = TestFiles.NewFolder();
        var store = new JsonRunLogStore(folder.Path);
        RunRecord Run(string id, int minute) => new()
        {
            Id = id,
            StartedUtc = new DateTimeOffset(2026, 11, 23, 1, minute, 0, TimeSpan.Zero),
            FinishedUtc = new DateTimeOffset(2026, 11, 23, 1, minute, 30, TimeSpan.Zero),
            Outcome = "completed",
            Machine = "simulator",
            Settings = new JobSettings { ImagePath = "/a.png", Passes = 2 },
        };

        store.Save(Run("old", 1));
        store.Save(Run("new", 2));

        var history = store.History();
        Assert.Equal(["new", "old"], history.Select(r => r.Id));
        Assert.Equal(2, history[0].Settings.Passes);
        Assert.Equal(30, history[0].ElapsedSeconds);
    }

    [Fact]
    public void History_DamagedFile_LeftOut()
    {
        using var folder = TestFiles.NewFolder();
        File.WriteAllText(Path.Combine(folder.Path, "run-bad.json"), "{ not json");

        Assert.Empty(new JsonRunLogStore(folder.Path).History());
    }
}

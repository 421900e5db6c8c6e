using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;

namespace LaserEngrave.Core.Tests.Marks;

/// <summary>The sample counter: advanced by a completed run only, never back, kept in a file with the settings.</summary>
public sealed class MarkCounterTests : IDisposable
{
    private readonly string _folder = Directory.CreateTempSubdirectory("mark-counter-").FullName;

    public void Dispose() => Directory.Delete(_folder, recursive: true);

    private MarkCounter Counter => new(Path.Combine(_folder, "settings", MarkCounter.FileName));

    [Fact]
    public void Next_NoFileYet_IsOne()
    {
        Assert.Equal(1, Counter.Next());
    }

    [Fact]
    public void Complete_TenCopiesFromOne_NextIsEleven()
    {
        Assert.Equal(11, Counter.Complete(1, 10));
        Assert.Equal(11, Counter.Next());
    }

    [Fact]
    public void Burned_CompletedRunsOnly_ANewBatchStartIsNotABurn()
    {
        Counter.Complete(1, 10);
        Counter.Complete(11, 5);
        Counter.Set(100);

        Assert.True(Counter.Burned(1, 1));
        Assert.True(Counter.Burned(15, 3));
        Assert.False(Counter.Burned(16, 84));
        Assert.False(Counter.Burned(100, 1));
        Assert.Equal(100, Counter.Next());
        Assert.Contains("\"burned\": [[1, 15]]", File.ReadAllText(Counter.Path), StringComparison.Ordinal);
    }

    [Theory]
    [InlineData("{ \"next\": 3, \"burned\": 7 }")]
    [InlineData("{ \"next\": 3, \"burned\": [[5, 2]] }")]
    [InlineData("{ \"next\": 3, \"burned\": [[1]] }")]
    public void Burned_BadList_OneLineNamingTheFile(string text)
    {
        Directory.CreateDirectory(Path.GetDirectoryName(Counter.Path)!);
        File.WriteAllText(Counter.Path, text);

        var error = Assert.Throws<MarkException>(() => Counter.Burned(1, 1));

        Assert.Equal($"{Counter.Path}: \"burned\" must be a list of [first, last] pairs", error.Message);
    }

    [Fact]
    public void Complete_AnOlderRunCompletingLate_NeverMovesTheCounterBack()
    {
        Counter.Complete(1, 10);

        Assert.Equal(11, Counter.Complete(3, 2));
    }

    [Fact]
    public void Next_BrokenFile_IsRefusedNamingIt()
    {
        Directory.CreateDirectory(Path.GetDirectoryName(Counter.Path)!);
        File.WriteAllText(Counter.Path, "{ \"next\": -3 }");

        var ex = Assert.Throws<MarkException>(() => Counter.Next());

        Assert.Contains(MarkCounter.FileName, ex.Message);
    }

    [Theory]
    [InlineData("[5]")]
    [InlineData("7")]
    public void Next_FileThatIsNotAnObject_IsRefusedNamingIt(string text)
    {
        Directory.CreateDirectory(Path.GetDirectoryName(Counter.Path)!);
        File.WriteAllText(Counter.Path, text);

        var ex = Assert.Throws<MarkException>(() => Counter.Next());

        Assert.Contains(MarkCounter.FileName, ex.Message);
        Assert.Contains("\"next\" must be a whole number", ex.Message);
    }

    [Theory]
    [InlineData(RunOutcome.Completed, 11)]
    [InlineData(RunOutcome.Aborted, 1)]
    [InlineData(RunOutcome.Failed, 1)]
    public void AfterRun_OfAMarksJob_AdvancesOnlyWhenItCompleted(RunOutcome outcome, int next)
    {
        var job = Path.Combine(_folder, "job", MarkLayout.JobFileName);
        Directory.CreateDirectory(Path.GetDirectoryName(job)!);
        MarkManifest.Write(Path.Combine(_folder, "job", MarkLayout.ManifestFileName), new MarkManifest(Counter.Path, 1, 10, []));

        MarkManifest.AfterRun(job, outcome == RunOutcome.Completed);

        Assert.Equal(next, Counter.Next());
    }

    [Fact]
    public void AfterRun_AbortedThenResumedToCompletion_BurnsAndCountsTheNumbersItStartedWith()
    {
        var folder = Path.Combine(_folder, "job");
        var layout = MarkLayout.Make(new MarkSpec { Text = "S-{n:000}", Code = CodeKind.DataMatrix, SizeMm = 2, Copies = 3 }, Counter.Next(), Context(), Core.Geometry.MachineProfile.Default, folder);
        var job = layout.Save(folder, Counter.Path);

        MarkManifest.AfterRun(job, completed: false);
        Assert.Equal(1, Counter.Next());

        // The resume runs the same job file: the same numbers, counted once it completes.
        Assert.Equal(["S-001", "S-002", "S-003"], MarkManifest.Beside(job)!.Marks.Where(m => m.Kind == "datamatrix").Select(m => m.Text));
        MarkManifest.AfterRun(job, completed: true);
        Assert.Equal(4, Counter.Next());
    }

    private static MarkContext Context() => new(0, null, DateTimeOffset.UnixEpoch, "test");
}

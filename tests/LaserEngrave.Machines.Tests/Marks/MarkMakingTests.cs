using LaserEngrave.Core.Geometry;
using LaserEngrave.Core.Jobs;
using LaserEngrave.Core.Marks;
using LaserEngrave.Machines.Marks;

namespace LaserEngrave.Machines.Tests.Marks;

/// <summary>The one sequence `laserengrave mark` and the app's Mark panel make marks with.</summary>
public sealed class MarkMakingTests : IDisposable
{
    private static readonly DateTimeOffset Noon = new(2026, 11, 27, 12, 0, 0, TimeSpan.Zero);
    private readonly string _dir = Path.Combine(Path.GetTempPath(), $"mark-making-{Guid.NewGuid():N}");

    public MarkMakingTests() => Directory.CreateDirectory(_dir);

    private MarkCounter Counter => new(Path.Combine(_dir, MarkCounter.FileName));

    private string Folder => Path.Combine(_dir, "job");

    public void Dispose() => Directory.Delete(_dir, recursive: true);

    private MarkOrder Order(MarkSpec spec) =>
        new(spec, Counter, new MarkContext(0, "W7", Noon, MachineProfile.Default.Name), MachineProfile.Default, Folder);

    [Fact]
    public async Task MakeAsync_TextAlone_NumberedFromTheCounterAndSavedWithoutTheTwin()
    {
        var made = await MarkMaking.MakeAsync(Order(new MarkSpec { Text = "{sample}-{n:000}", Copies = 3, Columns = 3 }), TestContext.Current.CancellationToken);

        Assert.Equal(Path.Combine(Folder, MarkLayout.JobFileName), made.JobFile);
        Assert.True(File.Exists(made.JobFile));
        Assert.True(File.Exists(Path.Combine(Folder, MarkLayout.ManifestFileName)));
        Assert.Equal(["W7-001", "W7-002", "W7-003"], made.Layout.Marks.Select(m => m.Text));
        Assert.Empty(made.Verdicts);
        Assert.Null(made.Unreadable);
        Assert.True(made.Job.EstimatedSeconds > 0);
        // Making a job does not advance the counter: a completed run does.
        Assert.Equal(1, Counter.Next());
    }

    [Fact]
    public async Task MakeAsync_StartAt_NumbersFromItAndWritesItToTheCounterWithTheJob()
    {
        var made = await MarkMaking.MakeAsync(Order(new MarkSpec { Text = "S-{n}" }) with { StartAt = 40 }, TestContext.Current.CancellationToken);

        Assert.Equal(40, made.Layout.FirstNumber);
        Assert.Equal("S-40", made.Layout.Marks[0].Text);
        Assert.Equal(40, Counter.Next());
    }

    [Fact]
    public async Task MakeAsync_RefusedWithAStart_LeavesTheCounterAndWritesNothing()
    {
        var ex = await Assert.ThrowsAsync<MarkException>(() => MarkMaking.MakeAsync(Order(new MarkSpec { Text = "S-{n}", Copies = 0 }) with { StartAt = 40 }, TestContext.Current.CancellationToken));

        Assert.StartsWith("copies 0 must be 1..", ex.Message, StringComparison.Ordinal);
        Assert.Equal(1, Counter.Next());
        Assert.False(Directory.Exists(Folder));
    }

    [Fact]
    public async Task MakeAsync_RefusalInTheFrontEndsWords_NamesItsBox()
    {
        var order = Order(new MarkSpec { Text = "S-{n}", Code = CodeKind.DataMatrix, SizeMm = 0 }) with { Name = f => f == "sizeMm" ? "code size" : f };

        var ex = await Assert.ThrowsAsync<MarkException>(() => MarkMaking.MakeAsync(order, TestContext.Current.CancellationToken));

        Assert.StartsWith("code size 0 must be above 0", ex.Message, StringComparison.Ordinal);
    }

    [Fact]
    public async Task MakeAsync_EmptyText_Refused()
    {
        var ex = await Assert.ThrowsAsync<MarkException>(() => MarkMaking.MakeAsync(Order(new MarkSpec { Text = string.Empty }), TestContext.Current.CancellationToken));

        Assert.Equal("give the mark's text", ex.Message);
    }

    [Fact]
    public async Task MakeAsync_BadStart_RefusedBeforeAnythingIsDrawn()
    {
        var ex = await Assert.ThrowsAsync<MarkException>(() => MarkMaking.MakeAsync(Order(new MarkSpec { Text = "S-{n}" }) with { StartAt = 0 }, TestContext.Current.CancellationToken));

        Assert.StartsWith("counter 0 must be 1..", ex.Message, StringComparison.Ordinal);
        Assert.False(Directory.Exists(Folder));
    }

    [Fact(Timeout = 300_000)]
    public async Task MakeAsync_CheckedCodeOfOneSpotModules_DoesNotReadSoNoJobAndNoStart()
    {
        var spec = new MarkSpec { Text = "S-{n:000}", Code = CodeKind.DataMatrix, ModuleUm = MachineProfile.Default.SpotDiameterUm, Label = false };

        var made = await MarkMaking.MakeAsync(Order(spec) with { Check = true, StartAt = 7 }, TestContext.Current.CancellationToken);

        Assert.Null(made.JobFile);
        Assert.NotNull(made.Unreadable);
        Assert.Equal("S-007", made.Unreadable.Text);
        Assert.False(File.Exists(Path.Combine(Folder, MarkLayout.JobFileName)));
        Assert.Equal(1, Counter.Next());
    }
}

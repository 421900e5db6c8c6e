using LaserEngrave.Cli.Commands;

namespace LaserEngrave.Cli.Tests.BadInput;

/// <summary>Every bad command line is refused with exit code 2 and one line, before anything opens or moves.</summary>
public class BadInputTests
{
    public static TheoryData<string[], int, string> BadInputs => BadInputTable.All();

    [Fact]
    public void Table_HasAtLeast150DistinctBadInputs()
    {
        var rows = BadInputTable.All().Select(row => string.Join('\u0001', row.Data.Item1)).ToList();

        Assert.True(rows.Count >= 150, $"{rows.Count} rows");
        Assert.Equal(rows.Count, rows.Distinct(StringComparer.Ordinal).Count());
    }

    [Theory]
    [MemberData(nameof(BadInputs))]
    public async Task Command_BadInput_OneLineAndExitCodeBeforeAnythingOpens(string[] args, int expectedExit, string fragment)
    {
        var files = BadInputFiles.Instance;
        var opened = 0;

        // The seam every machine passes through before it exists: the simulator included, so "nothing opened" means nothing moved.
        MachineOptions.Opening.Value = () => Interlocked.Increment(ref opened);
        var resolved = files.Resolve(args);
        using var stdout = new StringWriter();
        using var stderr = new StringWriter();

        // A command that blocked in a system call (a FIFO's open) would hang here; on a thread of its own it fails the test instead.
        var run = Task.Run(() => CliRunner.InvokeAsync(Program.BuildRoot(), resolved, stdout, stderr, TestContext.Current.CancellationToken), TestContext.Current.CancellationToken);
        var exit = await run.WaitAsync(TimeSpan.FromSeconds(60), TestContext.Current.CancellationToken);

        var error = stderr.ToString();
        Assert.True(exit == expectedExit, $"exit {exit}: {error}");
        Assert.Single(error.TrimEnd().Split('\n'));
        Assert.StartsWith("laserengrave: ", error, StringComparison.Ordinal);
        Assert.Contains(files.ResolveFragment(fragment), error, StringComparison.Ordinal);
        Assert.Equal(string.Empty, stdout.ToString());
        Assert.Equal(0, opened);
    }
}

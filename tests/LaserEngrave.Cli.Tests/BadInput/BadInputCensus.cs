namespace LaserEngrave.Cli.Tests.BadInput;

/// <summary>
/// Counts how many of the table's bad command lines are refused cleanly: exit code 2, one line on stderr, nothing on
/// stdout, within 30 s. Needs nothing but the table and the CLI, so it runs on older commits too (the figure before a
/// change): `dotnet test tests/LaserEngrave.Cli.Tests --filter FullyQualifiedName~BadInputCensus`.
/// With this table copied onto main at 6665baa, 146 of 262 were refused cleanly (9 blocked on a FIFO or ran a simulated
/// job past 30 s; the rest exited 0 or 1, or printed more than one line); after the validation work all 262 are.
/// Issue 21 grew the table to 407 rows (ValuesByWhatTheyAre: run logs, job files, simulator options, drawings, output
/// folders, decimal commas, typos, gate replies): on main at 469d48a 379 of 407 were refused cleanly (a null gate reply
/// crashed, edited logs ran or moved, scale(1e308) planned as NaN, a missing output folder exited 1, ...); now all 407.
/// </summary>
public class BadInputCensus
{
    private static readonly TimeSpan Limit = TimeSpan.FromSeconds(30);

    [Fact]
    public async Task BadInputs_Census_EveryOneRefusedCleanly()
    {
        var files = BadInputFiles.Instance;
        var rows = BadInputTable.All().Select(row => row.Data.Item1).ToList();
        var unclean = new List<string>();
        foreach (var args in rows)
        {
            var resolved = files.Resolve(args);
            using var stdout = new StringWriter();
            using var stderr = new StringWriter();
            using var stop = new CancellationTokenSource(Limit);

            // On a thread of its own: a command that blocks in a system call (a FIFO's open) must not take the test with it.
            var run = Task.Run(() => CliRunner.InvokeAsync(Program.BuildRoot(), resolved, stdout, stderr, stop.Token), TestContext.Current.CancellationToken);
            var finished = await Task.WhenAny(run, Task.Delay(Limit + TimeSpan.FromSeconds(5), TestContext.Current.CancellationToken));
            var what = string.Join(' ', args);
            if (finished != run)
            {
                unclean.Add($"{what}: hangs");
                continue;
            }

            var exit = await run;
            var lines = stderr.ToString().TrimEnd().Split('\n');
            if (exit != 2 || lines.Length != 1 || stdout.ToString().Length > 0)
            {
                unclean.Add($"{what}: exit {exit}, {lines.Length} line(s) on stderr, {stdout.ToString().Length} characters on stdout: {lines[0]}");
            }
        }

        var clean = rows.Count - unclean.Count;
        TestContext.Current.TestOutputHelper?.WriteLine($"bad inputs refused cleanly: {clean} of {rows.Count}");
        Assert.True(unclean.Count == 0, $"bad inputs refused cleanly: {clean} of {rows.Count}; not cleanly:\n{string.Join('\n', unclean)}");
    }
}

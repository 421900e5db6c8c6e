using System.CommandLine;
using System.Globalization;
using LaserEngrave.Core.Logging;

namespace LaserEngrave.Cli.Commands;

/// <summary>`laserengrave log show FILE [--json]` and `laserengrave log list [DIR | --log-dir DIR] [--csv]`: the run logs engrave writes.</summary>
internal static class LogCommand
{
    public static Command Create()
    {
        var command = new Command("log", "Show one run log, or list the runs in a log folder");
        command.Subcommands.Add(Show());
        command.Subcommands.Add(List());
        return command;
    }

    /// <summary>The --log-dir option of `log list` and `engrave`.</summary>
    public static Option<string?> LogDirOption() => new("--log-dir")
    {
        Description = $"Folder of the run logs (default: {RunLogStore.DefaultFolder})",
    };

    private static Command Show()
    {
        var file = new Argument<string>("FILE") { Description = "A run log: the .json file (or the .txt summary beside it)" };
        var json = new Option<bool>("--json") { Description = "Print the JSON record instead of the summary" };
        var command = new Command("show", "Print a run's summary (or its JSON record)") { file, json };
        command.SetAction(result =>
        {
            var record = RunLogStore.Read(result.GetRequiredValue(file));
            var output = result.InvocationConfiguration.Output;
            output.Write(result.GetValue(json) ? RunRecordJson.Serialize(record) + "\n" : RunSummaryText.Format(record));
            return CliRunner.Ok;
        });
        return command;
    }

    private static Command List()
    {
        var logDir = LogDirOption();
        var folder = new Argument<string?>("FOLDER") { Description = "The log folder (the same as --log-dir)", Arity = ArgumentArity.ZeroOrOne };
        var csv = new Option<bool>("--csv")
        {
            Description = "Print the runs as CSV for a spreadsheet (date, sample ID, image or drawing, size, origin, process, passes, outcome, duration, estimate, notes, log), decimal points, fields between commas",
        };
        var decimalComma = new Option<bool>("--decimal-comma")
        {
            Description = "With --csv: decimal commas and fields between semicolons, as Excel reads them where 1,5 is one and a half",
        };
        var command = new Command("list", "List the runs in the log folder, newest first") { folder, logDir, csv, decimalComma };
        command.SetAction(result =>
        {
            if (result.GetValue(folder) is { } given && result.GetValue(logDir) is { } other && given != other)
            {
                throw new UsageException($"give the log folder once: {given} or --log-dir {other}");
            }

            if (result.GetValue(decimalComma) && !result.GetValue(csv))
            {
                throw new UsageException("--decimal-comma is for the CSV: add --csv");
            }

            var dir = result.GetValue(folder) ?? result.GetValue(logDir);
            if (dir is not null && File.Exists(dir))
            {
                throw new UsageException($"{dir} is a file, not a log folder: `laserengrave log show {dir}` shows one run log");
            }

            if (dir is not null && !Directory.Exists(dir))
            {
                throw new UsageException($"{dir}: no such log folder");
            }

            var store = new RunLogStore(dir ?? RunLogStore.DefaultFolder);
            var output = result.InvocationConfiguration.Output;
            var entries = store.List();
            if (result.GetValue(csv))
            {
                foreach (var unreadable in entries.Where(e => e.Record is null))
                {
                    result.InvocationConfiguration.Error.WriteLine($"warning: {unreadable.Error}");
                }

                // The header alone when there are no runs: a spreadsheet still gets its columns.
                output.Write(RunHistoryRow.ToCsv(RunHistoryRow.From(entries), result.GetValue(decimalComma)));
                return CliRunner.Ok;
            }

            if (entries.Count == 0)
            {
                output.WriteLine($"no run logs in {store.Folder}");
                return CliRunner.Ok;
            }

            var c = CultureInfo.InvariantCulture;
            foreach (var entry in entries)
            {
                if (entry.Record is not { } r)
                {
                    result.InvocationConfiguration.Error.WriteLine($"warning: {entry.Error}");
                    continue;
                }

                var done = string.Create(c, $"{r.RunsDone}/{r.RunsTotal} runs");
                output.WriteLine(string.Create(
                    c,
                    $"{r.StartedAt:yyyy-MM-dd HH:mm}  {r.Outcome.ToString().ToLowerInvariant(),-9}  {done,-16}  {RunSummaryText.Duration(r.ActualSeconds),-14}  {r.SampleId ?? "-",-12}  {Path.GetFileName(r.Image.Path)}  {entry.Path}"));
            }

            return CliRunner.Ok;
        });
        return command;
    }
}

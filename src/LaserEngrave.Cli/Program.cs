using System.CommandLine;
using LaserEngrave.Cli.Commands;

namespace LaserEngrave.Cli;

internal static class Program
{
    public static async Task<int> Main(string[] args)
    {
        var root = BuildRoot();
        return await CliRunner.InvokeAsync(root, args, Console.Out, Console.Error).ConfigureAwait(false);
    }

    /// <summary>Every command of `laserengrave`; each lives in its own file under Commands/.</summary>
    internal static RootCommand BuildRoot()
    {
        var root = new RootCommand("LaserEngrave: plan, preview and engrave monochrome images on a Zaber X-Y stage with a gated laser.");
        root.Options.Add(CliOptions.Verbose);
        foreach (var command in CommandRegistry.All())
        {
            root.Subcommands.Add(command);
        }

        NumberParsers.Install(root);

        return root;
    }
}

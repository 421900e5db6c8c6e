using System.CommandLine;
using LaserEngrave.Cli.Commands;

namespace LaserEngrave.Cli;

/// <summary>The list of top-level commands, in the order `--help` shows them.</summary>
internal static class CommandRegistry
{
    public static IEnumerable<Command> All()
    {
        yield return InfoCommand.Create();
        yield return MaskCommand.Create();
        yield return PlanCommand.Create();
        yield return PreviewCommand.Create();
        yield return ProcessCommand.Create();
        yield return CalibrateCommand.Create();
        yield return PatternCommand.Create();
        yield return AlignCommand.Create();
        yield return BenchCommand.Create();
        yield return PortsCommand.Create();
        yield return StageCommand.Create();
        yield return LaserCommand.Create();
        yield return SimulatorCommand.Create();
        yield return MachineCommand.Create();
        yield return EngraveCommand.Create();
        yield return ReplayCommand.Create();
        yield return SweepCommand.Create();
        yield return SweepCommand.CreateFocusSeries();
        yield return MarkCommand.Create();
        yield return LogCommand.Create();
        foreach (var command in TestMoveCommands.All())
        {
            yield return command;
        }
    }
}

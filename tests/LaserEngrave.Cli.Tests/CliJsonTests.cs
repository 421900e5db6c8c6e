using LaserEngrave.Cli.Commands;
using LaserEngrave.Core.Imaging;

namespace LaserEngrave.Cli.Tests;

public sealed class CliJsonTests
{
    public static TheoryData<Type> Outputs =>
    [
        typeof(AlignSummary), typeof(CalibrationShowSummary), typeof(CalibrationSolveSummary), typeof(EngraveSummary), typeof(ImageInfo),
        typeof(JobSummary), typeof(LatencySummary), typeof(LayersSummary), typeof(MachineCheckSummary), typeof(MarkCommand.MarkSummary),
        typeof(ProcessSummary), typeof(SweepPlanSummary), typeof(SweepRunSummary), typeof(VectorSummary),
    ];

    // A published CLI starts precompiled; metadata built by reflection would be compiled at the first --json output.
    [Theory]
    [MemberData(nameof(Outputs))]
    public void Options_ACommandsOutput_DescribedByTheGeneratedContext(Type output)
    {
        var info = CliJson.Options.GetTypeInfo(output);

        Assert.Same(CliJsonContext.Default, info.OriginatingResolver);
    }
}

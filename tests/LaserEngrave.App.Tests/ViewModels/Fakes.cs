using LaserEngrave.App.Services;
using LaserEngrave.Core.Geometry;
using LaserEngrave.Devices.Abstractions;
using NSubstitute;

namespace LaserEngrave.App.Tests.ViewModels;

/// <summary>A machine of NSubstitute fakes: two axes that move where they are told, and a gate that acknowledges.</summary>
internal sealed class Fakes
{
    public Fakes()
    {
        X = Axis(1);
        Y = Axis(2);
        Stage = Substitute.For<IStage>();
        Stage.X.Returns(X);
        Stage.Y.Returns(Y);
        Gate = Substitute.For<ILaserGate>();
        Gate.IdentifyAsync(Arg.Any<CancellationToken>()).Returns("PICGATE FAKE");
        Gate.GetStateAsync(Arg.Any<CancellationToken>()).Returns(new LaserGateState(0, false, 1000, false));
        Connection = Substitute.For<IMachineConnection>();
        Connection.Stage.Returns(Stage);
        Connection.Gate.Returns(Gate);
        Connection.Profile.Returns(MachineProfile.Default);
        Connection.Description.Returns("fake machine");
        Connection.TimeProvider.Returns(TimeProvider.System);
        Factory = Substitute.For<IMachineConnectionFactory>();
        Factory.ConnectAsync(Arg.Any<MachineChoice>(), Arg.Any<MachineProfile>(), Arg.Any<CancellationToken>()).Returns(Connection);
    }

    public IStageAxis X { get; }

    public IStageAxis Y { get; }

    public IStage Stage { get; }

    public ILaserGate Gate { get; }

    public IMachineConnection Connection { get; }

    public IMachineConnectionFactory Factory { get; }

    private static IStageAxis Axis(byte number)
    {
        var axis = Substitute.For<IStageAxis>();
        long position = 0;
        axis.DeviceNumber.Returns(number);
        axis.IdentifyAsync(Arg.Any<CancellationToken>()).Returns(new AxisIdentity(number, 4212, 502, 0x80, 604724));
        axis.GetPositionAsync(Arg.Any<CancellationToken>()).Returns(_ => position);
        axis.MoveAbsoluteAsync(Arg.Any<long>(), Arg.Any<CancellationToken>()).Returns(c => position = c.Arg<long>());
        axis.HomeAsync(Arg.Any<CancellationToken>()).Returns(_ => position = 0);
        return axis;
    }
}
